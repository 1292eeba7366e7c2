"""Notebook kernels forked from a process that has imported the course's libraries
(sandbox.course.prefork): they run cells in the folder and environment their launcher was
started with, count their compiles where the lesson runner asks, take interrupts, exit with
their launcher, and without a server are ordinary kernels."""

import os
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("ipykernel")
pytest.importorskip("jupyter_client")

from jupyter_client.kernelspec import KernelSpecManager  # noqa: E402
from jupyter_client.manager import KernelManager  # noqa: E402

from sandbox import compile_cache  # noqa: E402
from sandbox.compile_cache import COMPILE_LOG  # noqa: E402
from sandbox.course import prefork  # noqa: E402

pytestmark = pytest.mark.skipif(not prefork.available(), reason="no fork here")


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    folder = tmp_path_factory.mktemp("prefork")
    address = folder / "server"
    env = {**os.environ, "PREFORK_MARK": "from the server"}
    with prefork.Server(address, env):
        yield folder, prefork.write_spec(folder / "kernels", address)


def start(specs: Path, cwd: Path, env: dict | None = None, options=()) -> tuple:
    manager = KernelManager(
        kernel_name="python3",
        kernel_spec_manager=KernelSpecManager(kernel_dirs=[str(specs)], ensure_native_kernel=False),
    )
    manager.start_kernel(cwd=str(cwd), env={**os.environ, **(env or {})}, extra_arguments=options)
    client = manager.client()
    client.start_channels()
    client.wait_for_ready(timeout=60)
    return manager, client


def run(client, code: str, timeout: float = 60) -> dict:
    """Execute ``code``; its stdout and the reply's content."""
    msg_id = client.execute(code)
    out = []
    while True:
        msg = client.get_iopub_msg(timeout=timeout)
        if msg["parent_header"].get("msg_id") != msg_id:
            continue
        if msg["msg_type"] == "stream":
            out.append(msg["content"]["text"])
        if msg["msg_type"] == "status" and msg["content"]["execution_state"] == "idle":
            break
    reply = client.get_shell_msg(timeout=timeout)
    return {"out": "".join(out), **reply["content"]}


def gone(pid: int, seconds: float) -> bool:
    """Whether process ``pid`` ends within ``seconds``."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.05)
    return False


def stop(manager, client) -> None:
    client.stop_channels()
    manager.shutdown_kernel(now=True)


def test_a_forked_kernel_runs_in_its_launchers_folder_and_environment(server, tmp_path):
    _, specs = server
    options = ["--HistoryManager.hist_file=:memory:"]  # as the notebook client asks
    manager, client = start(specs, tmp_path, {"LESSON_MARK": "this lesson"}, options)
    try:
        code = (
            "import os, sys\n"
            "print(os.getcwd())\n"
            "print(os.environ.get('LESSON_MARK'), os.environ.get('PREFORK_MARK'))\n"
            "print('sandbox.world' in sys.modules, os.getpid() != os.getppid())\n"
            "print(get_ipython().history_manager.hist_file)"
        )
        reply = run(client, code)
        assert reply["status"] == "ok"
        cwd, marks, loaded, history = reply["out"].splitlines()
        assert history == ":memory:"  # the kernel's own options reach it
        assert Path(cwd).resolve() == tmp_path.resolve()
        # the launcher's environment replaces the server's; the libraries came imported
        assert marks == "this lesson None"
        assert loaded == "True True"
    finally:
        stop(manager, client)


def test_each_kernel_starts_from_the_server_not_from_the_last_lesson(server, tmp_path):
    _, specs = server
    first, client = start(specs, tmp_path)
    try:
        assert run(client, "import sandbox; sandbox.LEFT_BY_A_LESSON = 1")["status"] == "ok"
    finally:
        stop(first, client)
    second, client = start(specs, tmp_path)
    try:
        reply = run(client, "import sandbox; print(hasattr(sandbox, 'LEFT_BY_A_LESSON'))")
        assert reply["out"].strip() == "False"
    finally:
        stop(second, client)


def test_a_forked_kernel_logs_its_compiles_where_its_launcher_says(server, tmp_path):
    _, specs = server
    log = tmp_path / "lesson.compiles"
    manager, client = start(specs, tmp_path, {COMPILE_LOG: str(log)})
    try:
        code = (
            "from sandbox.jit import JIT_ENABLED, njit\n"
            "print(JIT_ENABLED)\n"
            "def add_one(x):\n    return x + 1\n"
            "print(njit(cache=False)(add_one)(1))"
        )
        reply = run(client, code)
        assert reply["status"] == "ok"
    finally:
        stop(manager, client)
    enabled, result = reply["out"].split()
    assert result == "2"
    if enabled == "True":
        assert log.read_text(encoding="utf-8").split() == ["add_one"]


def test_an_interrupt_reaches_a_forked_kernel(server, tmp_path):
    _, specs = server
    manager, client = start(specs, tmp_path)
    try:
        msg_id = client.execute("import time\ntime.sleep(60)")
        deadline = time.monotonic() + 30
        while True:  # the cell is running
            msg = client.get_iopub_msg(timeout=30)
            if msg["parent_header"].get("msg_id") == msg_id and msg["msg_type"] == "execute_input":
                break
            assert time.monotonic() < deadline
        time.sleep(0.2)
        manager.interrupt_kernel()
        reply = client.get_shell_msg(timeout=20)["content"]
        assert reply["status"] == "error" and reply["ename"] == "KeyboardInterrupt"
    finally:
        stop(manager, client)


def test_a_forked_kernel_exits_with_its_launcher(server, tmp_path):
    _, specs = server
    manager, client = start(specs, tmp_path)
    pid = int(run(client, "import os; print(os.getpid())")["out"])
    assert pid != manager.provisioner.process.pid  # the kernel is not the launched process
    stop(manager, client)  # kills the launcher
    assert gone(pid, 10.0), f"kernel {pid} still running 10 s after its launcher was killed"


def test_without_a_server_the_launcher_is_an_ordinary_kernel(tmp_path):
    specs = prefork.write_spec(tmp_path / "kernels", tmp_path / "nobody-listens")
    manager, client = start(specs, tmp_path)
    try:
        reply = run(client, "import sys; print('sandbox.world' in sys.modules, sys.executable)")
        loaded, executable = reply["out"].split()
        assert loaded == "False"
        assert executable == sys.executable
    finally:
        stop(manager, client)


def test_the_launcher_starts_without_site_packages_and_imports_only_the_standard_library(
    tmp_path,
):
    # the kernel spec runs prefork.py by its path with -S: no third-party module, not even the
    # sandbox package, can be imported there, so the launcher must not need one
    import json
    import subprocess

    specs = prefork.write_spec(tmp_path / "kernels", tmp_path / "nobody-listens")
    python, flag, path = json.loads((specs / "python3" / "kernel.json").read_text())["argv"][:3]
    assert flag == "-S" and Path(path).resolve() == Path(prefork.__file__).resolve()
    usage = subprocess.run([python, "-S", path], capture_output=True, text=True, timeout=60)
    assert usage.returncode == 1 and "usage: python -m sandbox.course.prefork" in usage.stderr
    names = "sorted({m.split('.')[0] for m in sys.modules})"
    code = f"import json, runpy, sys; runpy.run_path({path!r}); print(json.dumps({names}))"
    listed = subprocess.run([python, "-S", "-c", code], capture_output=True, text=True, timeout=60)
    assert listed.returncode == 0, listed.stderr
    loaded = set(json.loads(listed.stdout))
    assert "socket" in loaded  # the launcher's own imports ran
    assert not loaded & {"sandbox", "numpy", "numba", "matplotlib", "ipykernel", "zmq"}


def test_a_kernel_asked_for_with_other_import_settings_starts_afresh(server, tmp_path):
    _, specs = server
    manager, client = start(specs, tmp_path, {"SANDBOX_JIT": "0"})
    try:
        code = (
            "import sys\n"
            "print('sandbox.world' in sys.modules)\n"
            "import sandbox.jit\n"
            "print(sandbox.jit.JIT_ENABLED)"
        )
        reply = run(client, code)
        assert reply["out"].split() == ["False", "False"]
        pid = int(run(client, "import os; print(os.getpid())")["out"])
        assert pid == manager.provisioner.process.pid  # the launcher became the kernel
    finally:
        stop(manager, client)


def test_the_server_exits_when_the_command_that_started_it_is_gone(tmp_path):
    # a command killed without its cleanup leaves no server behind
    import subprocess

    address = tmp_path / "server"
    code = (
        "import os, sys, time\n"
        "from pathlib import Path\n"
        "from sandbox.course import prefork\n"
        f"server = prefork.Server(Path({str(address)!r}), dict(os.environ)).__enter__()\n"
        "print(server.process.pid, flush=True)\n"
        "os._exit(0)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    pid = int(done.stdout.split()[0])
    if not gone(pid, 15.0):
        os.kill(pid, 9)
        pytest.fail("the server outlived the command that started it by 15 s")


def loaded_steps(specs: Path, cwd: Path) -> list[int]:
    """How many compiled versions of the one-call steps (iterative, soft) a new kernel has."""
    code = (
        "from sandbox import step\n"
        "print(len(step.fast_step.signatures), len(step.soft_step.signatures))"
    )
    manager, client = start(specs, cwd)
    try:
        return [int(n) for n in run(client, code)["out"].split()]
    finally:
        stop(manager, client)


@pytest.mark.skipif(not compile_cache.is_warm(), reason="the steps are not compiled yet")
def test_with_the_engine_a_kernel_starts_with_the_steps_loaded(tmp_path):
    # `sandbox lessons` on a compiled machine: the server loads the lessons' families from the
    # cache once, and every kernel has them (no loading of its own); without, none has
    address = tmp_path / "engine"
    for engine in (True, False):
        with prefork.Server(address, dict(os.environ), engine=engine):
            loaded = loaded_steps(prefork.write_spec(tmp_path / f"k-{engine}", address), tmp_path)
        assert all(loaded) if engine else not any(loaded), (engine, loaded)


@pytest.mark.skipif(not compile_cache.is_warm(), reason="the steps are not compiled yet")
def test_a_server_loads_the_engine_when_asked(tmp_path):
    # a first `sandbox lessons`: the server starts while the warmup compiles and loads the
    # engine once asked (request_engine); kernels forked after that start with it
    address = tmp_path / "later"
    with prefork.Server(address, dict(os.environ)):
        specs = prefork.write_spec(tmp_path / "kernels", address)
        before = loaded_steps(specs, tmp_path)
        assert prefork.request_engine(address)
        after = loaded_steps(specs, tmp_path)
    assert not any(before) and all(after), (before, after)
    assert not prefork.request_engine(tmp_path / "no-server")  # nothing listens: False


@pytest.mark.skipif(not compile_cache.is_warm(), reason="the steps are not compiled yet")
def test_asked_early_the_server_loads_all_but_the_soft_step(tmp_path):
    # a first `sandbox lessons` on two cores: once every family but the soft step's is
    # compiled, the server loads those, and the lessons without the soft step start with them;
    # asked again when the warmup is done, it loads the soft step too
    address = tmp_path / "early"
    with prefork.Server(address, dict(os.environ)):
        specs = prefork.write_spec(tmp_path / "kernels", address)
        assert prefork.request_engine(address, early=True)
        early = loaded_steps(specs, tmp_path)
        assert prefork.request_engine(address)
        late = loaded_steps(specs, tmp_path)
    assert early[0] > 0 and early[1] == 0, early
    assert all(late), late
