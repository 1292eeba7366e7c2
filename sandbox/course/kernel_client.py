"""A lesson kernel's client that is ready as soon as its kernel has answered.

Before the first cell, the notebook client waits for its kernel (``wait_for_ready``): it asks
for the kernel's info until the answer comes and the IOPub channel carries the kernel's status,
then reads IOPub until nothing more has come for 0.2 s. On this machine's local sockets a
kernel's start-up messages come within a few milliseconds, and those 0.2 s were a pause in every
lesson in which neither the lesson nor the command did anything (0.5 s from start to ready, of
which the kernel's own start takes 0.1 s of CPU). Here the wait after the answer is 20 ms; a
message that comes later still does no harm, as the notebook client reads only the replies to
its own requests.
"""

from __future__ import annotations

import math
import time
from queue import Empty

from jupyter_client.blocking import BlockingKernelClient

SETTLE = 0.02  # s without an IOPub message after the kernel's answer: ready
CONNECTED = 0.2  # s the kernel's status may take to arrive on IOPub after its answer


class ReadyClient(BlockingKernelClient):
    """jupyter_client's blocking client with a shorter wait for the kernel's start-up messages
    (:data:`SETTLE`)."""

    def wait_for_ready(self, timeout: float | None = None) -> None:
        """Return once the kernel has answered a ``kernel_info`` request on the shell channel
        and IOPub is connected (its status came), and IOPub has then been quiet for
        :data:`SETTLE` s. Raises RuntimeError if the kernel dies or ``timeout`` (s) passes.
        With a jupyter_client whose pieces moved, its own wait."""
        if not hasattr(self, "_handle_kernel_info_reply"):
            return super().wait_for_ready(timeout)
        deadline = time.monotonic() + (math.inf if timeout is None else timeout)
        while True:
            self.kernel_info()
            try:
                reply = self.shell_channel.get_msg(timeout=1.0)
            except Empty:
                reply = None
            if reply is not None and reply["msg_type"] == "kernel_info_reply":
                try:
                    self.iopub_channel.get_msg(timeout=CONNECTED)
                except Empty:  # IOPub not connected yet: ask again
                    pass
                else:
                    self._handle_kernel_info_reply(reply)
                    break
            if not self.is_alive():
                raise RuntimeError("Kernel died before replying to kernel_info")
            if time.monotonic() > deadline:
                raise RuntimeError(f"Kernel didn't respond in {timeout:g} seconds")
        while True:  # the rest of what the kernel said while starting
            try:
                self.iopub_channel.get_msg(timeout=SETTLE)
            except Empty:
                return
