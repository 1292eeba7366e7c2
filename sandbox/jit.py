"""One source, two speeds: hot loops are plain Python compiled by numba.

Set ``SANDBOX_JIT=0`` in the environment to run the very same functions as plain Python, for
stepping through them in a debugger or reading a traceback line by line.

Compiled code is cached on disk (``cache=True``) so only the first run compiles. numba checks a
cached function only against its own source file, so after editing a kernel, a function in
another module that calls it could load stale machine code. To rule that out the cache lives in
a folder named after a hash of every kernel module's source (``numba-<hash>``): any edit to a
kernel starts a fresh cache.

Where that folder lives: the first writable one of ``$NUMBA_CACHE_DIR`` (when set), the
package's ``__pycache__``, the user's cache folder (``$XDG_CACHE_HOME`` or ``~/.cache``, then
``physics-sandbox``), and a private folder in the system's temporary folder (created mode 0700
and used only when it belongs to this user, since compiled code is loaded from it). Writable is
tried (a file is created), not read from permission bits. On a locked-down machine where none
is writable, kernels compile afresh in every process (no cache). Only the choice is made on
import; nothing is compiled until a kernel first runs, and the one-line note saying where the
cache went (temporary folder, or none) is printed by the command line after the scene has been
validated (:func:`take_cache_note`).
"""

from __future__ import annotations

import hashlib
import os
import shutil
import stat
import tempfile
from pathlib import Path

JIT_ENABLED: bool = os.environ.get("SANDBOX_JIT", "1") != "0"

_PACKAGE = Path(__file__).resolve().parent
CACHE_FOLDER: Path | None = None  # where compiled kernels are cached (None: no cache)
_note: str | None = None


def kernel_sources_hash() -> str:
    """A short hash of the source of every module of the package that compiles kernels."""
    digest = hashlib.sha256()
    for path in sorted(_PACKAGE.rglob("*.py")):
        text = path.read_bytes()
        if b"@njit" in text:
            digest.update(path.relative_to(_PACKAGE).as_posix().encode())
            digest.update(text)
    return digest.hexdigest()[:16]


def writable_folder(folder: Path) -> bool:
    """Create ``folder`` (and parents) if needed and try writing a file in it."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError:
        return False
    return True


def private_temp_folder() -> Path | None:
    """``<temp>/physics-sandbox-<user>``, created 0700; None unless it is ours and private."""
    try:
        user = str(os.getuid()) if hasattr(os, "getuid") else os.environ.get("USERNAME", "user")
        base = Path(tempfile.gettempdir()) / f"physics-sandbox-{user}"
        base.mkdir(mode=0o700, exist_ok=True)
        info = os.lstat(base)
    except (OSError, FileNotFoundError):
        return None
    if not stat.S_ISDIR(info.st_mode):  # a symlink or a file planted there
        return None
    if hasattr(os, "getuid") and (info.st_uid != os.getuid() or info.st_mode & 0o022):
        return None  # someone else's, or writable by others: never load code from it
    return base


def _user_cache_base() -> Path | None:
    root = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(root) / "physics-sandbox" if root and not root.startswith("~") else None


def choose_cache_folder(key: str) -> tuple[Path | None, str | None]:
    """The cache folder for kernel-source hash ``key`` and a note when it is a fallback.

    Tidies stale ``numba-*`` siblings in the folders the sandbox owns (never in
    ``$NUMBA_CACHE_DIR``).
    """
    name = f"numba-{key}"
    user_dir = os.environ.get("NUMBA_CACHE_DIR")
    tried = []
    if user_dir:
        if writable_folder(Path(user_dir) / name):
            return Path(user_dir) / name, None
        tried.append(f"NUMBA_CACHE_DIR {user_dir!r}")
    for base in (_PACKAGE / "__pycache__", _user_cache_base()):
        if base is not None and writable_folder(base / name):
            _tidy(base, name)  # the user's cache folder is as usual as the package's
            return base / name, _fallback_note(tried, base / name) if user_dir else None
        if base is not None:
            tried.append(str(base))
    base = private_temp_folder()
    if base is not None and writable_folder(base / name):
        _tidy(base, name)
        return base / name, _fallback_note(tried, base / name)
    return None, (
        f"no writable folder for the compile cache ({', '.join(tried)} and a private one in "
        "the temporary folder): kernels compile afresh in every run"
    )


def _fallback_note(tried: list[str], folder: Path) -> str:
    return f"compile cache in {str(folder)!r} ({', '.join(tried)} not writable)"


def _tidy(base: Path, keep: str) -> None:
    """Drop stale cache folders of earlier kernel sources."""
    for old in base.glob("numba-*"):
        if old.name != keep:
            shutil.rmtree(old, ignore_errors=True)


def take_cache_note() -> str | None:
    """The note about where the compile cache went (None when all is as usual), once."""
    global _note
    text, _note = _note, None
    return text


if JIT_ENABLED:
    import numba

    CACHE_FOLDER, _note = choose_cache_folder(kernel_sources_hash())
    if CACHE_FOLDER is not None:
        numba.config.CACHE_DIR = str(CACHE_FOLDER)
    _CACHE = CACHE_FOLDER is not None

    def njit(*args, **kwargs):
        """``numba.njit(cache=True)`` (accepts the same arguments as numba.njit); without a
        writable cache folder, ``cache=False``."""
        kwargs["cache"] = kwargs.get("cache", True) and _CACHE
        if args and callable(args[0]) and len(args) == 1 and not kwargs.get("_signature"):
            return numba.njit(**kwargs)(args[0])
        return numba.njit(*args, **kwargs)

else:

    def njit(*args, **kwargs):
        """Plain-Python stand-in for ``numba.njit`` (SANDBOX_JIT=0)."""
        if args and callable(args[0]) and len(args) == 1:
            return args[0]
        return lambda f: f


def entry(function, *args):
    """The compiled machine code of ``function`` for the types of ``args``, callable from Python
    without numba's type dispatch (a call with ten arrays then costs about a microsecond less);
    ``function`` itself when compiling is off. Call it only with arguments of those same types
    (array dtype, dimensions and layout): nothing checks them any more."""
    if not JIT_ENABLED:
        return function
    signature = tuple(function.typeof_pyval(a) for a in args)
    return function.compile(signature)
