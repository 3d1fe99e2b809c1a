"""The parts of a graded run that the grader hosts in its own process: the run's private core and
its recorder (the bag recorder's node). Two processes fewer to start for each seed: about a
second and a half of CPU each on the machines classes use.

    core = HostedCore(); await core.start()         # core.url: on a free loopback port
    recorder = HostedRecorder(path, core.url, lockstep_url, seed=1); await recorder.start()
    ...
    await recorder.stop()                           # the file is finished
    await core.stop()
"""

from __future__ import annotations

import asyncio
import re
import time
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

import uvicorn

from services.bag.recorder import Recorder
from services.bag.recording import TopicSelection
from services.bag.writer import BagWriter
from services.core.app import create_app
from services.core.server import core_config
from services.core.settings import CoreSettings
from services.runtime.server import bind
from services.runtime.settings import NodeSettings

__all__ = ["NOT_RECORDED", "HostedCore", "HostedRecorder"]

NOT_RECORDED = "camera"
"""Topics the recorder leaves out (a regex): the simulator renders only while someone reads it."""
_START_TIMEOUT_S = 10.0
_STOP_GRACE_S = 3.0


class HostedCore:
    """A core served from this process's event loop, on a free loopback port, without a token and
    without the protocol endpoints (nobody but the run's nodes uses it)."""

    def __init__(self) -> None:
        self._socket = bind("127.0.0.1", 0)
        self.port: int = self._socket.getsockname()[1]
        self.url = f"http://127.0.0.1:{self.port}"
        self._settings = CoreSettings(host="127.0.0.1", port=self.port, token="")
        self._server = uvicorn.Server(core_config(create_app(self._settings), self._settings))
        self._task: asyncio.Task[None] | None = None

    async def start(self) -> None:
        self._task = asyncio.get_running_loop().create_task(self._server.serve(sockets=[self._socket]))
        deadline = time.monotonic() + _START_TIMEOUT_S
        while not self._server.started:
            if self._task.done() or time.monotonic() > deadline:
                raise RuntimeError("the grading core did not start")
            await asyncio.sleep(0.005)

    async def stop(self) -> None:
        """Stop serving; the run's processes are gone, so connections close at once (a lingering
        one is cut after a moment)."""
        if self._task is None:
            return
        self._server.should_exit = True
        try:
            await asyncio.wait_for(asyncio.shield(self._task), _STOP_GRACE_S)
        except TimeoutError:
            self._server.force_exit = True
            await self._task
        self._task = None


class HostedRecorder:
    """The bag recorder's node, recording every topic but the camera into ``path``."""

    def __init__(self, path: Path, core_url: str, lockstep_url: str, *, seed: int, command_line: str) -> None:
        metadata = {
            "skydeck_version": _version(),
            "command_line": command_line,
            "core_url": core_url,
            "started": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
            "world_seed": str(seed),
        }
        self.path = path
        self.writer = BagWriter.create(path, metadata=metadata)
        settings = NodeSettings(host="127.0.0.1", port=0, token="", core_url=core_url, lockstep_url=lockstep_url)
        selection = TopicSelection(all_topics=True, exclude=re.compile(NOT_RECORDED))
        self.node = Recorder(self.writer, selection, settings=settings)

    async def start(self) -> None:
        await self.node.start()

    async def stop(self) -> None:
        """Stop recording and finish the file (its summary and index)."""
        try:
            await self.node.stop()
        finally:
            self.writer.close()


def _version() -> str:
    try:
        return version("skydeck")
    except PackageNotFoundError:
        return "unknown"
