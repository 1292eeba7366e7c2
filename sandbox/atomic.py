"""Write files whole or not at all, one by one or as a set.

One file: :func:`atomic_write` writes a temporary file beside the target, then renames it over.

A set of files (everything one command writes: a trace, a GIF, a PNG, a comparison's folder):
inside ``with output_set():`` every :func:`atomic_write` still writes its temporary file, but the
renames wait for the end of the block, where they happen together, after every file is complete.
If the block raises (an error, a full disk, Ctrl-C, SIGTERM turned into an exception), every
temporary file is removed, folders the set created are removed again, and the old files stay as
they were: a failed command writes nothing new. A failure while renaming (rare: the folder
vanished, a target is a folder) puts back the files already replaced.

Every output of the sandbox (traces, PNG, GIF, saved scenes) goes through here.
"""

from __future__ import annotations

import contextlib
import contextvars
import os
import secrets
import signal
import stat
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

# the process umask, read once (os.umask can only be read by setting it)
_UMASK = os.umask(0o022)
os.umask(_UMASK)

_MODES = ("w", "wt", "wb")
# a temporary file is created new, or not at all, as tempfile.mkstemp creates its files
_NEW_FILE = os.O_WRONLY | os.O_CREAT | os.O_EXCL
_NEW_FILE |= getattr(os, "O_BINARY", 0) | getattr(os, "O_NOINHERIT", 0)  # Windows
_SIGNALS = {getattr(signal, s) for s in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, s)}


class OutputSet:
    """Files staged under temporary names, renamed over their targets together by :meth:`commit`.

    Use through :func:`output_set`; :func:`atomic_write` stages into the active set.
    ``written`` lists the targets after a successful commit.
    """

    def __init__(self) -> None:
        self._staged: dict[str, str] = {}  # target -> complete temporary file beside it
        self._folders: list[str] = []  # folders this set created, outermost first
        self.written: list[Path] = []

    def stage(self, target: str, tmp: str) -> None:
        """Record the complete temporary file ``tmp`` for ``target`` (a later one replaces it)."""
        old = self._staged.pop(target, None)
        if old is not None:
            _remove(old)
        self._staged[target] = tmp

    def make_folder(self, path: str | os.PathLike) -> Path:
        """Create ``path`` and missing parents; the ones created are removed if the set fails."""
        path = Path(path).absolute()
        missing = [p for p in (path, *path.parents) if not p.exists()]
        for p in reversed(missing):
            p.mkdir()
            self._folders.append(str(p))
        if not path.is_dir():
            raise NotADirectoryError(20, "not a folder", str(path))
        return path

    def commit(self) -> list[Path]:
        """Rename every staged file over its target; on failure restore the targets replaced."""
        items = list(self._staged.items())
        self._staged.clear()
        with _signals_deferred():
            backups: dict[str, str] = {}
            done: list[str] = []
            try:
                for target, tmp in items:  # keep each old file until every rename succeeded
                    if os.path.isfile(target):
                        with contextlib.suppress(OSError):
                            os.link(target, tmp + ".old")
                            backups[target] = tmp + ".old"
                for target, tmp in items:
                    os.chmod(tmp, _permissions(target))
                    os.replace(tmp, target)
                    done.append(target)
            except BaseException:
                for target in reversed(done):
                    if target in backups:
                        os.replace(backups.pop(target), target)
                    else:
                        _remove(target)
                for _, tmp in items:
                    _remove(tmp)
                for backup in backups.values():
                    _remove(backup)
                self._remove_folders()
                raise
            for backup in backups.values():
                _remove(backup)
            for folder in sorted({os.path.dirname(t) for t, _ in items}):
                _sync_folder(folder)
        self._folders.clear()
        self.written = [Path(t) for t, _ in items]
        return self.written

    def discard(self) -> None:
        """Remove every staged temporary file and the folders this set created."""
        with _signals_deferred():
            for tmp in self._staged.values():
                _remove(tmp)
            self._staged.clear()
            self._remove_folders()

    def _remove_folders(self) -> None:
        for folder in reversed(self._folders):
            with contextlib.suppress(OSError):
                os.rmdir(folder)  # only if empty: never a file that was there before
        self._folders.clear()


_ACTIVE: contextvars.ContextVar[OutputSet | None] = contextvars.ContextVar(
    "sandbox_output_set", default=None
)


@contextlib.contextmanager
def output_set() -> Iterator[OutputSet]:
    """Write every file of the block as one set: all renamed at the end, or none.

    Inside an active set, joins it (the outermost block commits).
    """
    active = _ACTIVE.get()
    if active is not None:
        yield active
        return
    outputs = OutputSet()
    token = _ACTIVE.set(outputs)
    try:
        yield outputs
    except BaseException:
        outputs.discard()
        raise
    finally:
        _ACTIVE.reset(token)
    outputs.commit()


def make_folder(path: str | os.PathLike) -> Path:
    """Create folder ``path`` (and parents); inside :func:`output_set`, undone if the set fails."""
    active = _ACTIVE.get()
    if active is not None:
        return active.make_folder(path)
    path = Path(path)
    path.mkdir(parents=True, exist_ok=True)
    return path


@contextlib.contextmanager
def atomic_write(
    path: str | os.PathLike,
    mode: str = "w",
    *,
    encoding: str = "utf-8",
    newline: str | None = None,
) -> Iterator[IO[Any]]:
    """Open a temporary file next to ``path`` for writing; on success rename it over ``path``.

    ``mode`` is ``"w"`` (text, ``encoding`` and ``newline`` as for :func:`open`) or ``"wb"``.
    When the ``with`` block raises, the temporary file is removed, ``path`` is left as it was
    (absent if it did not exist) and the exception propagates. The data is flushed and fsynced
    before the rename, so ``path`` holds either the old content or the complete new content.
    Inside :func:`output_set` the rename waits for the end of the set. An ``OSError`` without a
    file name (a write to a full disk) is given ``path`` as its ``filename``.
    """
    if mode not in _MODES:
        raise ValueError(f"atomic_write: mode must be one of {', '.join(_MODES)}, got {mode!r}")
    target = os.path.abspath(os.fspath(path))
    folder = os.path.dirname(target)
    active = _ACTIVE.get()
    tmp = fd = handle = None
    try:
        # the name before the file: a Ctrl-C at any moment finds the temporary file's name known
        # and it is removed below (tempfile.mkstemp gives both at once: one arriving as it
        # returns left the file behind)
        tmp = os.path.join(folder, f".{os.path.basename(target)}.{secrets.token_hex(8)}.tmp")
        fd = os.open(tmp, _NEW_FILE, 0o600)
        if "b" in mode:
            handle = os.fdopen(fd, "wb")
        else:
            handle = os.fdopen(fd, "w", encoding=encoding, newline=newline)
        with handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        if active is not None:
            active.stage(target, tmp)
            return
        os.chmod(tmp, _permissions(target))
        os.replace(tmp, target)
    except OSError as err:
        if fd is None and isinstance(err, FileExistsError):
            tmp = None  # that name was taken (2^-64): the file is not ours to remove
        _discard(handle, fd, tmp)
        raise _named(err, path) from None
    except BaseException:
        _discard(handle, fd, tmp)
        raise
    _sync_folder(folder)


def atomic_write_text(path: str | os.PathLike, text: str, encoding: str = "utf-8") -> None:
    """Write ``text`` to ``path`` atomically (whole or not at all)."""
    with atomic_write(path, "w", encoding=encoding) as f:
        f.write(text)


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically (whole or not at all)."""
    with atomic_write(path, "wb") as f:
        f.write(data)


def _named(err: OSError, path: str | os.PathLike) -> OSError:
    if err.filename is None or str(err.filename).endswith(".tmp"):
        err.filename = os.fspath(path)
    return err


@contextlib.contextmanager
def _signals_deferred() -> Iterator[None]:
    """Hold SIGINT, SIGTERM and SIGHUP while files are renamed or removed (POSIX): a signal
    arriving then is delivered when the block ends, so cleanup itself is never cut short."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, _SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _permissions(target: str) -> int:
    """Keep the permissions of a file being replaced; a new file gets the umask's default."""
    try:
        return stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        return 0o666 & ~_UMASK


def _discard(handle: IO[Any] | None, fd: int | None, tmp: str | None) -> None:
    """Close and remove a temporary file that will not be renamed, as far as it was made."""
    with contextlib.suppress(OSError):
        if handle is not None:
            handle.close()
        elif fd is not None:
            os.close(fd)
    if tmp is not None:
        _remove(tmp)


def _remove(tmp: str) -> None:
    with contextlib.suppress(OSError):  # already gone, or cleanup that must not hide the cause
        os.unlink(tmp)


def _sync_folder(folder: str) -> None:
    """fsync the folder so the rename itself survives a crash (POSIX; a no-op elsewhere)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
