"""Notebook kernels that start with the course's libraries already imported.

Every lesson runs in a fresh kernel, and each kernel spent about a second and a half of CPU
importing the same libraries (IPython and the kernel, numpy, numba, matplotlib, the engine)
before its first cell ran: a third of a short lesson. Here one process imports them once
(:func:`serve`); each kernel is a fork of it (:func:`launch`), so it starts with all of that in
memory and shares nothing with the lessons before or after it: a fork is a copy, taken before
any lesson ran.

The kernel spec (:func:`write_spec`) runs :func:`launch` in a small process of its own, the
one the notebook client starts, signals and stops: it passes its connection file, working
folder, environment and standard streams to the server, which forks the kernel, and then
waits until the kernel has exited, passing on an interrupt. When the small process is killed,
the kernel sees its end of the connection close and exits too. Where kernels are not forked
(:func:`available`: Linux only) or no server answers, the small process becomes an ordinary
kernel (``python -m ipykernel_launcher``).

Nothing is compiled in the server: kernels load the engine's compiled code themselves, from the
cache, as any process does.
"""

from __future__ import annotations

import json
import os
import signal
import socket
import sys
import threading
from pathlib import Path

# imported once in the server, before any fork: what every lesson's kernel needs
PRELOAD = (
    "numpy",
    "matplotlib.pyplot",
    "ipykernel.kernelapp",
    "ipykernel.ipkernel",
    "ipykernel.zmqshell",
    "ipykernel.debugger",  # the kernel's debugger class, resolved by every kernel as it starts
    "ipywidgets",
    "sandbox.lessonkit",
    "sandbox.world",
    "sandbox.scene",
    "sandbox.render",
    "sandbox.recording",
)

# what the preloaded modules read from the environment when imported (numba's settings, whether
# to compile, the compile cache's folder, matplotlib's backend, where modules are found): a
# kernel whose environment differs in any of these is not forked but started afresh
IMPORT_TIME = ("NUMBA_", "SANDBOX_JIT", "MPL", "PYTHON", "HOME", "XDG_CACHE_HOME")
START = 10.0  # s, the longest a server is waited for before lessons start without it


def available() -> bool:
    """Whether kernels are forked here: on Linux (Unix sockets that pass descriptors). Not on
    macOS, where a process that has loaded Apple's system libraries (numpy's Accelerate) must
    not go on in a fork without exec, nor on Windows, which has no fork."""
    return sys.platform.startswith("linux") and hasattr(socket, "send_fds")


def write_spec(folder: Path, address: Path) -> Path:
    """A kernel spec ``python3`` under ``folder`` whose kernels are forked by the server
    listening at ``address``. Returns the folder of kernel specs."""
    spec = folder / "python3"
    spec.mkdir(parents=True, exist_ok=True)
    # this file run by its path without site-packages: the small process imports nothing but
    # the standard library, not the sandbox package (0.1 s of CPU a lesson, 0.03 s this way)
    argv = [sys.executable, "-S", str(Path(__file__).resolve()), "launch", str(address)]
    kernel = {
        "argv": [*argv, "{connection_file}"],
        "display_name": "Python 3",
        "language": "python",
        "metadata": {"debugger": False},
    }
    (spec / "kernel.json").write_text(json.dumps(kernel, indent=1), encoding="utf-8")
    return folder


class Server:
    """The forking server, running in a process of its own while the lessons run
    (``with Server(address, env):``). It is ready to fork once it has imported
    :data:`PRELOAD`; a kernel asked for before then waits."""

    def __init__(self, address: Path, env: dict[str, str], engine: bool = False) -> None:
        import subprocess

        self.address = address
        self.process = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "sandbox.course.prefork",
                "serve",
                str(address),
                str(os.getpid()),
                *(["engine"] if engine else []),
            ],
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )

    def __enter__(self) -> Server:
        """Wait (at most :data:`START` s) until the server listens: a kernel asked for before
        then would be an ordinary one."""
        import time

        deadline = time.monotonic() + START
        while not self.address.exists() and self.process.poll() is None:
            if time.monotonic() > deadline:
                break
            time.sleep(0.01)
        return self

    def __exit__(self, *exc: object) -> None:
        self.process.terminate()
        self.process.wait()
        self.address.unlink(missing_ok=True)


def serve(address: str, parent: int, engine: bool = False) -> None:
    """Listen at ``address``, import :data:`PRELOAD` (and with ``engine``, load the compiled
    steps: :func:`load_engine`), then fork a kernel for each request, until terminated or the
    process ``parent`` (the command that started it) is gone."""
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(address)
    listener.listen(16)
    import importlib

    for name in PRELOAD:
        try:
            importlib.import_module(name)
        except ImportError:  # a kernel imports it itself (or reports that it cannot)
            pass
    if engine:
        load_engine()
    signal.signal(signal.SIGCHLD, signal.SIG_IGN)  # kernels are reaped as they exit
    signal.signal(signal.SIGTERM, lambda *_: os._exit(0))
    listener.settimeout(1.0)
    while True:
        try:
            connection, _ = listener.accept()
        except TimeoutError:
            if os.getppid() != parent:  # the lessons' command is gone: so is the server
                os._exit(0)
            continue
        connection.settimeout(None)
        try:
            request, fds = _receive(connection)
        except (OSError, ValueError):
            connection.close()
            continue
        if request.get("engine"):  # the lessons' kernels are compiled now (request_engine)
            load_engine(bool(request.get("early")))
            _reply(connection, "loaded")
            continue
        pid = 0  # none forked: the launcher starts an ordinary kernel
        if _imported_with(request["env"]) == _imported_with(os.environ):
            pid = os.fork()
            if pid == 0:
                listener.close()
                _kernel(connection, request, fds)  # never returns
        for fd in fds:
            os.close(fd)
        _reply(connection, str(pid))


def _reply(connection: socket.socket, line: str) -> None:
    """Answer one request with a line, and close the connection."""
    try:
        connection.sendall(f"{line}\n".encode())
    except OSError:
        pass
    connection.close()


def request_engine(address: Path, timeout: float = 120.0, early: bool = False) -> bool:
    """Have the server at ``address`` load the compiled engine now (:func:`load_engine`), once
    what the lessons need is in the cache (``early``: all but the soft step's kernels, which
    a first run's warmup compiles last): a server started while it was being compiled
    (``sandbox lessons`` on a new machine) imports its libraries meanwhile. Returns when the
    server has loaded it (whether it answered): kernels asked for in the meantime wait, and
    start with it."""
    request = json.dumps({"engine": True, "early": early}) + "\n"
    try:
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as connection:
            connection.settimeout(timeout)
            connection.connect(str(address))
            connection.sendall(request.encode())
            return connection.recv(64).startswith(b"loaded")
    except OSError:
        return False


def load_engine(early: bool = False) -> None:
    """Load from the cache what the lessons run, so that every kernel starts with it: each
    family of :data:`sandbox.warmup.LESSON_FAMILIES`, stepped once on a small world (the
    iterative and soft steps in one call and stage by stage, the other solvers, continuous
    collision, the integrators with forces), and the kernels lessons call on their own
    (:func:`sandbox.warmup.helpers`); then a first figure drawn, which loads the fonts and
    mathtext's parser. A kernel otherwise loads its share itself, lesson after lesson. Only
    when the cache holds them (the caller knows): else this process would compile them, for a
    minute. ``early``: all but what a first run's warmup compiles last
    (:data:`sandbox.warmup.LATE_FAMILIES` and :func:`sandbox.warmup.record_kernels`); called
    again later, what was loaded already costs nothing."""
    from io import BytesIO

    import matplotlib.pyplot as plt

    from sandbox.warmup import LATE_FAMILIES, helpers, lesson_kernels, warm_families, worlds

    try:
        families = [f for f in worlds(lessons=True) if not early or f[0] not in LATE_FAMILIES]
        warm_families(families, report=lambda line: None)
        if early:
            lesson_kernels()
        else:
            helpers()
    except Exception:  # a kernel loads it itself (or reports why it cannot)
        pass
    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0], [0.0, 1.0], label="$v_0$")
    ax.set(title="$e^2 h$", xlabel="t (s)", yscale="log")
    ax.legend()
    fig.tight_layout()
    fig.savefig(BytesIO(), format="png")
    plt.close(fig)


def _receive(connection: socket.socket) -> tuple[dict, list[int]]:
    """One request: a JSON line (connection file, options, folder, environment) and three
    descriptors (the launcher's standard streams); or ``{"engine": true}`` alone
    (:func:`request_engine`)."""
    data, fds, _, _ = socket.recv_fds(connection, 1 << 20, 3)
    while not data.endswith(b"\n"):
        more = connection.recv(1 << 20)
        if not more:
            raise ValueError("request cut short")
        data += more
    request = json.loads(data)
    if len(fds) != 3 and not request.get("engine"):
        raise ValueError("expected three descriptors")
    return request, fds


def _kernel(connection: socket.socket, request: dict, fds: list[int]) -> None:
    """In the forked child: become the kernel the launcher asked for, then exit."""
    code = 1
    try:
        signal.signal(signal.SIGCHLD, signal.SIG_DFL)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.setsid()
        for target, fd in enumerate(fds):
            os.dup2(fd, target)
            os.close(fd)
        os.chdir(request["cwd"])
        os.environ.clear()
        os.environ.update(request["env"])
        _follow_environment()
        watch = threading.Thread(target=_exit_with, args=(connection,), daemon=True)
        watch.start()
        from ipykernel.kernelapp import IPKernelApp

        sys.argv = ["ipykernel_launcher", "-f", request["connection_file"], *request["options"]]
        parent = os.environ.get("JPY_PARENT_PID")  # read by the kernel's class when imported
        if parent:
            sys.argv.append(f"--IPKernelApp.parent_handle={parent}")
        IPKernelApp.launch_instance()
        code = 0
    except SystemExit as end:
        code = end.code if isinstance(end.code, int) else 0
    except BaseException:
        import traceback

        traceback.print_exc()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)


def _imported_with(env) -> dict[str, str]:
    """The variables of ``env`` that modules read when imported (:data:`IMPORT_TIME`)."""
    return {name: value for name, value in env.items() if name.startswith(IMPORT_TIME)}


def _follow_environment() -> None:
    """What the preloaded modules read from the environment when imported, read again from the
    kernel's own: where its compiles are logged (:data:`sandbox.compile_cache.COMPILE_LOG`)."""
    from sandbox.compile_cache import COMPILE_LOG
    from sandbox.jit import JIT_ENABLED

    if JIT_ENABLED:
        from sandbox.jit import NOTICE

        NOTICE.log = os.environ.get(COMPILE_LOG) or None


def _exit_with(connection: socket.socket) -> None:
    """Exit the kernel when its launcher has gone (its end of the connection closed)."""
    while True:
        try:
            if not connection.recv(4096):
                break
        except OSError:
            break
    os._exit(1)


def launch(address: str, connection_file: str, options: list[str]) -> int:
    """The process the notebook client starts: ask the server for a forked kernel, then stay
    until it exits, passing on interrupts. Without a server, become an ordinary kernel.
    ``options`` are the kernel's own command-line options (the notebook client adds some)."""
    try:
        connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        connection.connect(address)
        request = {
            "connection_file": connection_file,
            "options": options,
            "cwd": os.getcwd(),
            "env": dict(os.environ),
        }
        data = (json.dumps(request) + "\n").encode()
        socket.send_fds(connection, [data], [0, 1, 2])
        reply = b""
        while not reply.endswith(b"\n"):
            more = connection.recv(64)
            if not more:
                raise OSError("no kernel forked")
            reply += more
        pid = int(reply)
        if pid <= 0:
            raise ValueError("not forked: other import-time settings")
    except (OSError, ValueError):
        argv = [sys.executable, "-m", "ipykernel_launcher", "-f", connection_file, *options]
        os.execv(sys.executable, argv)
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda number, _: _signal(pid, number))
    while True:  # the kernel holds the other end until it exits
        try:
            if not connection.recv(4096):
                return 0
        except InterruptedError:
            continue
        except OSError:
            return 0


def _signal(pid: int, number: int) -> None:
    try:
        os.kill(pid, number)
    except ProcessLookupError:
        pass
    if number == signal.SIGTERM:
        sys.exit(0)


if __name__ == "__main__":
    if sys.argv[1:2] == ["serve"]:
        serve(sys.argv[2], int(sys.argv[3]), sys.argv[4:5] == ["engine"])
    elif sys.argv[1:2] == ["launch"]:
        sys.exit(launch(sys.argv[2], sys.argv[3], sys.argv[4:]))
    else:
        usage = "serve ADDRESS PID [engine] | launch ADDRESS FILE [OPTION ...]"
        sys.exit(f"usage: python -m sandbox.course.prefork {usage}")
