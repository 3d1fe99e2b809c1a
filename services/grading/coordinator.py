"""The coordinator of a lockstep run (:mod:`services.runtime.lockstep`): the processes of the run
connect to it, it steps the simulator and waits, after each step, until the run has settled.

    coordinator = Coordinator()
    url = await coordinator.start()          # SKYDECK_LOCKSTEP_URL for every process of the run
    ...start the simulator and the nodes...
    await coordinator.wait_for_processes(count, timeout_s=30)
    await coordinator.settle(after=await coordinator.step("start"))
    for _ in range(ticks):
        await coordinator.settle(after=await coordinator.step("advance"))
    await coordinator.stop()

Settled: every process reports it has nothing to do and, for every topic between two nodes of
the run, the reader has received as many messages as the publisher handed it. The first settle
after a step tells each process what the step sent its nodes and the new sim time: it moves its
nodes' clocks once that has arrived and been handled (:mod:`services.runtime.lockstep.agent`). Per-channel counts
taken once from each process are enough: links are ordered, so a message is either counted at
both ends or at neither, and a process that has nothing to do stays so until a message reaches
it. A run that cannot settle (a node that loops, or floods until messages are dropped) is let
go on after ``settle_timeout_s``, and the run says it was not kept in lockstep.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import logging
from collections import Counter
from dataclasses import dataclass, field

from pydantic import ValidationError
from starlette.applications import Starlette
from starlette.routing import WebSocketRoute
from starlette.websockets import WebSocket, WebSocketDisconnect

from services.runtime.lockstep.frames import (
    ChannelCount,
    HelloFrame,
    NodeCounts,
    ReportFrame,
    SettleFrame,
    StepFrame,
    SteppedFrame,
    StepWhat,
    process_frames,
)
from services.runtime.server import AppServer
from services.runtime.settings import ProcessSettings
from shared_models.errors import SkydeckError

__all__ = ["Coordinator", "LockstepError", "Settling"]

logger = logging.getLogger("skydeck.grading")

_PATH = "/lockstep"
_REPORT_WAIT_S = 2.0  # how long a process may take to settle before it answers "not yet"


class LockstepError(SkydeckError):
    """The run's simulator is gone or never came (the message says which)."""


@dataclass
class Settling:
    """How the run's settling went so far: how many times it did not settle, and why last."""

    lost: int = 0
    last_reason: str = ""
    stuck: list[int] = field(default_factory=list)
    """The processes (pids) still busy, or not answering, when the run last did not settle."""


@dataclass(eq=False)
class _Process:
    websocket: WebSocket
    pid: int
    stepper: bool = False
    nodes: list[str] = field(default_factory=list)
    pending: dict[int, asyncio.Future[ReportFrame | SteppedFrame]] = field(default_factory=dict)
    gone: asyncio.Event = field(default_factory=asyncio.Event)


class Coordinator:
    """Serves the run's lockstep socket on loopback and drives the run (see the module docstring)."""

    def __init__(self, *, settle_timeout_s: float = 10.0) -> None:
        self.settle_timeout_s = settle_timeout_s
        self.processes: list[_Process] = []
        self.settling = Settling()
        self._ids = itertools.count(1)
        self._joined = asyncio.Event()
        self._server: AppServer | None = None

    # -- serving ----------------------------------------------------------------------------------

    async def start(self) -> str:
        """Serve on a free loopback port; returns the URL processes connect to."""
        app = Starlette(routes=[WebSocketRoute(_PATH, self._serve)])
        self._server = AppServer(app, ProcessSettings(host="127.0.0.1", port=0), what="the lockstep coordinator")
        await self._server.start()
        return f"ws://127.0.0.1:{self._server.port}{_PATH}"

    async def stop(self) -> None:
        for process in list(self.processes):
            with contextlib.suppress(RuntimeError, OSError):
                await process.websocket.close()
        if self._server is not None:
            await self._server.stop()
            self._server = None

    async def _serve(self, websocket: WebSocket) -> None:
        await websocket.accept()
        try:
            hello = process_frames.validate_json(await websocket.receive_text())
        except (ValidationError, WebSocketDisconnect, KeyError):
            return
        if not isinstance(hello, HelloFrame):
            return
        process = _Process(websocket, hello.pid, hello.stepper)
        self.processes.append(process)
        self._joined.set()
        try:
            while True:
                reply = process_frames.validate_json(await websocket.receive_text())
                if isinstance(reply, HelloFrame):
                    continue
                future = process.pending.pop(reply.id, None)
                if future is not None and not future.done():
                    future.set_result(reply)
        except (WebSocketDisconnect, ValidationError, KeyError, RuntimeError):
            pass
        finally:
            self.processes.remove(process)
            process.gone.set()
            for future in process.pending.values():
                if not future.done():
                    future.cancel()

    # -- asking -----------------------------------------------------------------------------------

    async def _ask(self, process: _Process, frame: SettleFrame | StepFrame) -> ReportFrame | SteppedFrame | None:
        """Send one request and wait for its reply; None if the process went away."""
        future: asyncio.Future[ReportFrame | SteppedFrame] = asyncio.get_running_loop().create_future()
        process.pending[frame.id] = future
        try:
            await process.websocket.send_text(frame.model_dump_json())
            return await future
        except (asyncio.CancelledError, RuntimeError, OSError, WebSocketDisconnect):
            if process.gone.is_set():
                return None
            raise
        finally:
            process.pending.pop(frame.id, None)

    def _stepper(self) -> _Process:
        for process in self.processes:
            if process.stepper:
                return process
        raise LockstepError("the simulator left the run (it exited: see its output)")

    async def wait_for_processes(self, count: int, timeout_s: float) -> bool:
        """Wait until ``count`` processes have joined; False if ``timeout_s`` passed first."""
        try:
            async with asyncio.timeout(timeout_s):
                while len(self.processes) < count:
                    self._joined.clear()
                    await self._joined.wait()
        except TimeoutError:
            return False
        return True

    async def reports(self, after: SteppedFrame | None = None) -> list[ReportFrame]:
        """One report from every process, each once it has settled (or said it has not);
        ``after`` a step: each is first told what the step sent its nodes and the new time."""
        answered, _ = await self._gather(after, timeout_s=None)
        return [report for _, report in answered]

    async def _gather(
        self, after: SteppedFrame | None, timeout_s: float | None
    ) -> tuple[list[tuple[_Process, ReportFrame]], list[_Process]]:
        """The reports of the processes that answered within ``timeout_s`` (None: however long),
        and the processes that did not (a process whose event loop is blocked never answers)."""
        processes = list(self.processes)
        if not processes:
            return [], []
        asks = [asyncio.ensure_future(self._ask(process, self._settle_frame(process, after))) for process in processes]
        _, late = await asyncio.wait(asks, timeout=timeout_s)
        for ask in late:
            ask.cancel()
        answered, silent = [], []
        for process, ask in zip(processes, asks, strict=True):
            if ask in late:
                silent.append(process)
                continue
            reply = ask.result()
            if isinstance(reply, ReportFrame):
                answered.append((process, reply))
                process.stepper = process.stepper or reply.stepper
                process.nodes = [node.name for node in reply.nodes]
        return answered, silent

    def _settle_frame(self, process: _Process, after: SteppedFrame | None) -> SettleFrame:
        if after is None:
            return SettleFrame(id=next(self._ids), max_wait_s=_REPORT_WAIT_S)
        mine = set(process.nodes)
        expect: dict[str, list[ChannelCount]] = {}
        for publisher in after.nodes:
            for topic, reader, count in publisher.sent:
                if reader in mine:
                    expect.setdefault(reader, []).append((topic, publisher.name, count))
        return SettleFrame(
            id=next(self._ids),
            max_wait_s=_REPORT_WAIT_S,
            clock_s=after.time_s,
            expect=[NodeCounts(name=name, received=received) for name, received in expect.items()],
        )

    async def settle(self, after: SteppedFrame | None = None, timeout_s: float | None = None) -> bool:
        """Wait until the run has settled (``after`` a step: once each process has handled what
        it sent and the new time); False (and counted in :attr:`settling`) if it has not within
        ``timeout_s`` (default: ``settle_timeout_s``)."""
        loop = asyncio.get_running_loop()
        deadline = loop.time() + (self.settle_timeout_s if timeout_s is None else timeout_s)
        while True:
            # A process answers within _REPORT_WAIT_S unless its event loop is blocked: past
            # the deadline and that, it counts as stuck.
            answered, silent = await self._gather(after, timeout_s=max(deadline - loop.time(), 0.0) + _REPORT_WAIT_S)
            after = None  # the step's messages and time are handled: from now on, plain settles
            reason = _unsettled([report for _, report in answered])
            if silent:
                reason = f"process {', '.join(str(p.pid) for p in silent)} did not answer"
            if reason is None:
                return True
            if loop.time() > deadline:
                self.settling.lost += 1
                self.settling.last_reason = reason
                self.settling.stuck = [p.pid for p, report in answered if not report.settled] + [p.pid for p in silent]
                logger.warning("lockstep: the run did not settle: %s", reason)
                return False

    async def step(self, what: StepWhat) -> SteppedFrame:
        """Have the simulator do one step; what it published (and the sim time after it)."""
        reply = await self._ask(self._stepper(), StepFrame(id=next(self._ids), what=what))
        if not isinstance(reply, SteppedFrame):
            raise LockstepError("the simulator left the run (it exited: see its output)")
        return reply


def _unsettled(reports: list[ReportFrame]) -> str | None:
    """Why the run has not settled, or None if it has."""
    for report in reports:
        if not report.settled:
            names = ", ".join(node.name for node in report.nodes) or "a process with no node yet"
            return f"{names}: still busy"
    nodes = {node.name for report in reports for node in report.nodes}
    sent: Counter[tuple[str, str, str]] = Counter()
    received: Counter[tuple[str, str, str]] = Counter()
    for report in reports:
        for node in report.nodes:
            for topic, reader, count in node.sent:
                if reader in nodes:
                    sent[(topic, node.name, reader)] += count
            for topic, publisher, count in node.received:
                if publisher in nodes:
                    received[(topic, publisher, node.name)] += count
    for key in sent.keys() | received.keys():
        if sent[key] != received[key]:
            topic, publisher, reader = key
            return f"{topic} from {publisher} to {reader}: {received[key]} of {sent[key]} arrived"
    return None
