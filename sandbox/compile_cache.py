"""Where compiled kernels are cached, and whether every kernel is there already ("warm").

Nothing here imports numba, so the command line can look at the cache before deciding how the
engine runs this time (:mod:`sandbox.jit` then points numba at :data:`CACHE_FOLDER`).

Compiled code is cached on disk so only the first run compiles. numba checks a cached function
only against its own source file, so after editing a kernel, a function in another module that
calls it could load stale machine code. To rule that out the cache lives in a folder named after
a hash of every kernel module's source (``numba-<hash>``): any edit to a kernel starts a fresh
cache.

Where that folder lives: the first writable one of ``$NUMBA_CACHE_DIR`` (when set), the
package's ``__pycache__``, the user's cache folder (``$XDG_CACHE_HOME`` or ``~/.cache``, then
``physics-sandbox``), and a private folder in the system's temporary folder (created mode 0700
and used only when it belongs to this user, since compiled code is loaded from it). Writable is
tried (a file is created), not read from permission bits. On a locked-down machine where none
is writable, kernels compile afresh in every process (no cache). The one-line note saying where
the cache went (temporary folder, or none) is printed by the command line after the scene has
been validated (:func:`take_cache_note`).

``sandbox warmup`` compiles every kernel and then leaves a file ``warm`` in the folder
(:func:`mark_warm`, :func:`is_warm`). Until it has, the kernels compiled ahead and shipped in the
package, where there are any that run here (:mod:`sandbox.prebuilt`), are used instead, from a
folder of their own beside it (``numba-<hash>-x86-64-v3``, marked warm).
"""

from __future__ import annotations

import hashlib
import os
import shutil
import stat
import tempfile
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent
WARM_FILE = "warm"
# environment variable naming a file: each compile is a line there (the compiled function's
# name) instead of the compile notice (:class:`sandbox.jit.CompileNotice`); ``sandbox lessons``
# sets it for each lesson, reports the count itself and keeps the lessons' pages clean
COMPILE_LOG = "SANDBOX_COMPILE_LOG"


# modules that set how the kernels compile (and are cached), without compiling any themselves
COMPILER_SETTINGS = ("jit.py", "vector_width.py", "ir_only.py")


def kernel_sources_hash() -> str:
    """A short hash of the source of every module of the package that compiles kernels or
    instructions compiled into them (numba's ``@intrinsic``), and of those that set how they
    compile (:data:`COMPILER_SETTINGS`)."""
    digest = hashlib.sha256()
    for path in sorted(_PACKAGE.rglob("*.py")):
        text = path.read_bytes()
        compiled = b"@njit" in text or b"@intrinsic" in text
        if compiled or path.relative_to(_PACKAGE).as_posix() in COMPILER_SETTINGS:
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
    for old in base.glob("numba-*"):  # numba-<hash>, and -<target> for the shipped kernels
        if old.name != keep and not old.name.startswith(keep + "-"):
            shutil.rmtree(old, ignore_errors=True)


def take_cache_note() -> str | None:
    """The note about where the compile cache went (None when all is as usual), once."""
    global _note
    text, _note = _note, None
    return text


_KEY = kernel_sources_hash()
CACHE_FOLDER, _note = choose_cache_folder(_KEY)
PREBUILT = False  # whether CACHE_FOLDER holds the kernels shipped in the package instead
_OWN = CACHE_FOLDER  # the cache folder for this very processor


def _choose_shipped() -> None:
    """Use the kernels shipped in the package (:mod:`sandbox.prebuilt`) where the cache for
    this very processor is not warm and they run here; where it is warm, that cache."""
    global CACHE_FOLDER, PREBUILT
    from sandbox import prebuilt

    if CACHE_FOLDER is None:
        return
    if (CACHE_FOLDER / WARM_FILE).exists():
        prebuilt.leave()  # started by a process that used them: this one has its own
        return
    shipped = prebuilt.use(CACHE_FOLDER, _KEY)
    if shipped is not None:
        CACHE_FOLDER, PREBUILT = shipped, True


_choose_shipped()


def own_processor() -> None:
    """Compile for this very processor from here on, into its own cache, not the shipped
    kernels' (``sandbox warmup``, before the engine is imported), and so do the processes this
    one starts."""
    global CACHE_FOLDER, PREBUILT
    from sandbox import prebuilt

    os.environ[prebuilt.SWITCH] = "off"
    prebuilt.leave()
    CACHE_FOLDER, PREBUILT = _OWN, False


def is_warm() -> bool:
    """Whether ``sandbox warmup`` has compiled every kernel into the cache folder."""
    return CACHE_FOLDER is not None and (CACHE_FOLDER / WARM_FILE).exists()


def step_kernel(shapes: int, joints: int, solver: str) -> str:
    """The one-call step (a kernel of :mod:`sandbox.step`) a world of ``shapes`` shapes and
    ``joints`` joints under ``solver`` runs: ``free_step`` when nothing can touch, else
    ``soft_step`` or ``fast_step``. The world chooses by it; the command line asks it before
    importing the engine (whether that kernel is compiled yet)."""
    if solver == "soft":
        return "soft_step"
    return "free_step" if shapes < 2 and joints == 0 else "fast_step"


def has_kernel(name: str) -> bool:
    """Whether an earlier run left compiled code of ``name``, a kernel of
    :mod:`sandbox.step` (``"fast_step"``, ``"soft_step"``), in the cache folder: numba's index
    file ``step.<name>-<line>.py<version>.nbi``. A large scene whose step is there loads it
    in a second or two, even before ``sandbox warmup`` has compiled everything."""
    return CACHE_FOLDER is not None and any(CACHE_FOLDER.rglob(f"step.{name}-*.nbi"))


def mark_warm() -> None:
    """Note that every kernel is compiled into the cache folder."""
    if CACHE_FOLDER is not None:
        (CACHE_FOLDER / WARM_FILE).write_text("every kernel compiled by sandbox warmup\n")
