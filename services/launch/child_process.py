"""One child of the launcher, as a process: started in its own process group (so stopping it
stops whatever it started, and a Ctrl-C in the terminal reaches only the launcher), its output
split into lines, its exit a future, and stopped as a group: SIGTERM, then SIGKILL.

The supervisor (:mod:`services.launch.supervisor`) decides *when* to start, wait, respawn and
stop; this module only knows *how*.
"""

from __future__ import annotations

import asyncio
import contextlib
import enum
import os
import shlex
import signal
import subprocess
import time
from collections.abc import Callable, Mapping, Sequence

from services.launch.errors import LaunchError
from services.runtime.http_client import HttpClient, HttpError

__all__ = ["ChildProcess", "Health", "describe_exit", "signal_group", "spawn"]

POLL_INTERVAL_S = 0.05
_HEALTH_REQUEST_TIMEOUT_S = 1.0
_DRAIN_TIMEOUT_S = 1.0
_LINE_LIMIT_BYTES = 2**20  # longer lines are forwarded in pieces


class Health(enum.Enum):
    """How waiting for a child's ``/health`` ended."""

    READY = "ready"
    EXITED = "exited"
    TIMEOUT = "timeout"
    STOPPING = "stopping"


class ChildProcess(asyncio.SubprocessProtocol):
    """One run of a child: splits its output into lines and says when it has exited.

    Exit is reported as soon as the process ends, even while a grandchild still holds its pipes
    (``asyncio.subprocess.Process.wait`` waits for the pipes too on Python 3.11).
    """

    def __init__(self, on_line: Callable[[str, bool], None]) -> None:
        loop = asyncio.get_running_loop()
        self.exited: asyncio.Future[int] = loop.create_future()
        self.finished: asyncio.Future[None] = loop.create_future()  # exited and pipes closed
        self.transport: asyncio.SubprocessTransport | None = None
        self._on_line = on_line
        self._buffers = {1: bytearray(), 2: bytearray()}

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        self.transport = transport  # type: ignore[assignment]

    def pipe_data_received(self, fd: int, data: bytes | bytearray) -> None:
        buffer = self._buffers[fd]
        buffer += data
        start = 0
        while (end := buffer.find(b"\n", start)) >= 0:
            self._emit(fd, buffer[start:end])
            start = end + 1
        del buffer[:start]
        if len(buffer) > _LINE_LIMIT_BYTES:
            self._emit(fd, buffer)
            buffer.clear()

    def pipe_connection_lost(self, fd: int, exc: Exception | None) -> None:
        if buffer := self._buffers.get(fd):
            self._emit(fd, buffer)
            buffer.clear()

    def process_exited(self) -> None:
        code = self.transport.get_returncode() if self.transport else None
        if not self.exited.done():
            self.exited.set_result(-1 if code is None else code)

    def connection_lost(self, exc: Exception | None) -> None:
        if not self.finished.done():
            self.finished.set_result(None)

    def _emit(self, fd: int, raw: bytes | bytearray) -> None:
        self._on_line(raw.decode("utf-8", errors="replace").rstrip("\r"), fd == 2)


    @property
    def running(self) -> bool:
        return not self.exited.done()

    @property
    def pid(self) -> int:
        if self.transport is None:
            raise LaunchError("internal: the process has no transport yet")
        return int(self.transport.get_pid())

    async def wait_healthy(
        self, http: HttpClient, url: str, timeout_s: float, stopping: Callable[[], bool]
    ) -> Health:
        """Poll ``url`` until 200, the process exits, ``timeout_s`` passes or ``stopping()``."""
        deadline = time.monotonic() + timeout_s
        while True:
            if self.exited.done():
                return Health.EXITED
            if stopping():
                return Health.STOPPING
            with contextlib.suppress(HttpError):
                response = await http.get(url, timeout_s=_HEALTH_REQUEST_TIMEOUT_S)
                if response.status == 200:
                    return Health.READY
            if time.monotonic() >= deadline:
                return Health.TIMEOUT
            await asyncio.wait({self.exited}, timeout=POLL_INTERVAL_S)

    async def terminate(self, timeout_s: float, on_kill: Callable[[], None]) -> int:
        """SIGTERM the group, SIGKILL it after ``timeout_s`` (telling ``on_kill``); then reap."""
        if self.running:
            signal_group(self.pid, signal.SIGTERM)
            await asyncio.wait({self.exited}, timeout=timeout_s)
            if self.running:
                on_kill()
                signal_group(self.pid, signal.SIGKILL)
        return await self.reap()

    async def reap(self) -> int:
        """The exit code, after killing what is left of the group (grandchildren) and reading
        the rest of the output."""
        code = await self.exited
        signal_group(self.pid, signal.SIGKILL)
        # Its last output, unless something outside its group still holds the pipes.
        await asyncio.wait({self.finished}, timeout=_DRAIN_TIMEOUT_S)
        if self.transport is not None:
            self.transport.close()
        return code


async def spawn(
    argv: Sequence[str], env: Mapping[str, str], on_line: Callable[[str, bool], None], *, what: str
) -> ChildProcess:
    """Start ``argv`` in its own session, its stdout and stderr lines going to ``on_line``."""
    loop = asyncio.get_running_loop()
    try:
        _, process = await loop.subprocess_exec(
            lambda: ChildProcess(on_line),
            *argv,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=dict(env),
            start_new_session=True,  # its own process group: killed as a whole, deaf to Ctrl-C
        )
    except OSError as error:
        raise LaunchError(f"cannot start {what} ({shlex.join(argv)}): {error}", node=what) from None
    return process


def signal_group(pgid: int, sig: signal.Signals) -> None:
    # The group's id is the leader's pid (start_new_session). The id stays reserved while any
    # member lives, so this cannot hit an unrelated process; an empty group is simply gone.
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, sig)


def describe_exit(code: int) -> str:
    if code < 0:
        with contextlib.suppress(ValueError):
            return f"signal {signal.Signals(-code).name}"
        return f"signal {-code}"
    return f"exit code {code}"
