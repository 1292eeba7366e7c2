"""The lesson kernels' client (sandbox.course.kernel_client): ready once its kernel has answered
and IOPub carries its status, without jupyter_client's 0.2 s of IOPub silence; a kernel that
dies is reported; and the lesson runner's kernels have all exited when its kernels() ends."""

import json
import os
import sys
import time
from pathlib import Path
from queue import Empty

import pytest

pytest.importorskip("ipykernel")
pytest.importorskip("jupyter_client")

from jupyter_client.kernelspec import KernelSpecManager  # noqa: E402
from jupyter_client.manager import KernelManager  # noqa: E402

from sandbox.course import kernel_client  # noqa: E402
from sandbox.course.catalogue import Lesson  # noqa: E402
from sandbox.course.runner import kernels, run_notebook  # noqa: E402

CLIENT = "sandbox.course.kernel_client.ReadyClient"


def manager(specs: Path, name: str = "python3") -> KernelManager:
    return KernelManager(
        kernel_name=name,
        kernel_spec_manager=KernelSpecManager(kernel_dirs=[str(specs)], ensure_native_kernel=False),
        client_class=CLIENT,
    )


class Channel:
    """A channel whose messages are given in advance; get_msg raises Empty once they are out
    (after waiting its timeout, as a quiet socket does, noted in ``waited``)."""

    def __init__(self, messages=()):
        self.messages = list(messages)
        self.waited = []

    def get_msg(self, timeout=None):
        if self.messages:
            return self.messages.pop(0)
        self.waited.append(timeout)
        raise Empty


class Fake(kernel_client.ReadyClient):
    """The client's waiting alone, on given channels."""

    def __init__(self, shell, iopub, alive=True):
        self.fake = (Channel(shell), Channel(iopub))
        self.alive, self.asked, self.info = alive, 0, None

    shell_channel = property(lambda self: self.fake[0])
    iopub_channel = property(lambda self: self.fake[1])

    def kernel_info(self):
        self.asked += 1

    def is_alive(self):
        return self.alive

    def _handle_kernel_info_reply(self, msg):
        self.info = msg


REPLY = {"msg_type": "kernel_info_reply", "content": {"status": "ok"}}
STATUS = {"msg_type": "status", "content": {"execution_state": "idle"}}


def test_ready_once_the_kernel_answers_and_iopub_is_quiet_for_a_moment():
    client = Fake([REPLY], [STATUS, STATUS, STATUS])
    start = time.monotonic()
    client.wait_for_ready(timeout=5)
    assert client.info is REPLY and client.asked == 1
    assert client.iopub_channel.messages == []  # the start-up messages were read
    # the last wait on IOPub is the short settle, not jupyter_client's 0.2 s
    assert client.iopub_channel.waited == [kernel_client.SETTLE]
    assert kernel_client.SETTLE < 0.2
    assert time.monotonic() - start < 1.0


def test_asks_again_until_iopub_is_connected():
    # the first answer comes before IOPub carries anything: ask again, as jupyter_client does
    client = Fake([REPLY, REPLY], [])
    client.iopub_channel.messages = []
    calls = []
    original = client.iopub_channel.get_msg

    def first_empty(timeout=None):
        calls.append(timeout)
        if len(calls) == 2:
            return STATUS
        return original(timeout)

    client.iopub_channel.get_msg = first_empty
    client.wait_for_ready(timeout=5)
    assert client.asked == 2 and client.info is REPLY


def test_another_jupyter_client_gets_its_own_wait(monkeypatch):
    # without the piece this wait uses (a jupyter_client whose internals moved), the client
    # waits as jupyter_client itself does
    from jupyter_client.blocking import BlockingKernelClient
    from jupyter_client.client import KernelClient

    waited = []
    monkeypatch.delattr(KernelClient, "_handle_kernel_info_reply", raising=False)
    monkeypatch.delattr(Fake, "_handle_kernel_info_reply")
    monkeypatch.setattr(
        BlockingKernelClient, "wait_for_ready", lambda self, t=None: waited.append(t)
    )
    client = Fake([REPLY], [STATUS])
    client.wait_for_ready(timeout=5)
    assert waited == [5] and client.asked == 0


def test_a_kernel_that_stops_answering_is_reported():
    with pytest.raises(RuntimeError, match="died"):
        Fake([], [], alive=False).wait_for_ready(timeout=5)


def test_a_kernel_that_dies_is_reported(tmp_path):
    dead = tmp_path / "kernels" / "dead"
    dead.mkdir(parents=True)
    spec = {"argv": [sys.executable, "-c", "import sys; sys.exit(3)"], "display_name": "dead"}
    (dead / "kernel.json").write_text(json.dumps(spec))
    km = manager(tmp_path / "kernels", "dead")
    km.start_kernel()
    client = km.client()
    client.start_channels()
    try:
        with pytest.raises(RuntimeError, match="died"):
            client.wait_for_ready(timeout=30)
    finally:
        client.stop_channels()
        km.shutdown_kernel(now=True)


def test_every_kernel_has_exited_when_the_runner_is_done(tmp_path):
    # run_notebook stops each kernel beside the next lesson; kernels() waits for them all
    lesson = tmp_path / "98_pid.py"
    lesson.write_text(
        "# %% [markdown]\n# # 98 Pid\n\n# %%\nimport os\nprint('pid', os.getpid())\n",
        encoding="utf-8",
    )
    outputs = tmp_path / "outputs"
    with kernels(tmp_path / "k", outputs) as specs:
        outcomes = [run_notebook(Lesson(lesson), outputs, specs) for _ in range(2)]
    assert all(o.ok for o in outcomes), [o.error for o in outcomes]
    page = json.loads((outputs / "98_pid" / "98_pid.ipynb").read_text(encoding="utf-8"))
    text = "".join(page["cells"][1]["outputs"][0]["text"])
    pid = int(text.split()[1])
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)
