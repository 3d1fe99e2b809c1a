"""A process's side of a lockstep run: it tells the coordinator when it has nothing left to do.

Every node of a process started with ``SKYDECK_LOCKSTEP_URL`` joins the process's one agent
(:func:`join`), which connects to the coordinator there and answers its requests
(:mod:`.frames`): ``settle`` is answered once the process is *settled*, and ``step`` by the
process that simulates the world (the one that set a :data:`Stepper`).

Settled means: no node has work (a message queued for a callback or a callback running, a timer
on sim time that is due or running, a link still connecting), nothing counted in
:data:`~services.runtime.lockstep.activity.ACTIVITY` runs, and that stays so, counts unchanged,
over a few turns of the event loop (a task woken by a callback runs within a turn or two; what
it does shows in the counts). The coordinator adds the rest: every message a node was sent has
arrived (the counts of both ends agree), so nothing is on its way either.

The nodes' sim clocks are moved by the agent, not by ``/clock`` messages (which arrive on a
socket of their own, in no order with the sensors'): after a step, once the step's messages
have arrived and been handled, then the clock, so timers always see the step's sensor data.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import os
from collections.abc import Callable
from typing import Protocol

from pydantic import ValidationError
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosed, InvalidHandshake, WebSocketException

from services.runtime.lockstep.activity import ACTIVITY
from services.runtime.lockstep.frames import (
    HelloFrame,
    NodeCounts,
    ReportFrame,
    SettleFrame,
    SteppedFrame,
    StepWhat,
    coordinator_frames,
)

__all__ = ["LockstepNode", "Stepper", "join", "leave", "set_stepper"]

logger = logging.getLogger("skydeck.runtime")

Stepper = Callable[[StepWhat], float]
"""What the simulator does for a ``step`` request; returns the sim time after it."""

_CONFIRM_TURNS = 4  # event-loop turns a settled state must last, counts unchanged
_SPIN_TURNS = 8  # turns to look again at once before napping (work on threads needs the CPU)
_NAP_S = 0.0005
_CONNECT_TRIES = 100
_CONNECT_PAUSE_S = 0.05

Counts = tuple[tuple[str, tuple[tuple[str, str, int], ...], tuple[tuple[str, str, int], ...]], ...]


class LockstepNode(Protocol):
    """What the agent asks of a node."""

    def get_name(self) -> str: ...

    def lockstep_state(self) -> tuple[bool, list[tuple[str, str, int]], list[tuple[str, str, int]]]:
        """(busy, sent per topic and reader, received per topic and publisher)."""
        ...

    def lockstep_set_clock(self, time_s: float) -> None:
        """Move the node's sim clock to ``time_s`` (nothing if it runs on the wall clock)."""
        ...


class _Agent:
    """The process's agent (see the module docstring)."""

    def __init__(self, url: str) -> None:
        self.url = url
        self.nodes: list[LockstepNode] = []
        self.stepper: Stepper | None = None
        self._task: asyncio.Task[None] | None = None

    def start(self) -> None:
        if self._task is None:
            self._task = asyncio.get_running_loop().create_task(self._run())

    async def stop(self) -> None:
        task, self._task = self._task, None
        if task is not None:
            task.cancel()
            await asyncio.gather(task, return_exceptions=True)

    async def _run(self) -> None:
        websocket = await self._connect()
        if websocket is None:
            return
        async with websocket:
            await websocket.send(HelloFrame(pid=os.getpid(), stepper=self.stepper is not None).model_dump_json())
            with contextlib.suppress(ConnectionClosed):
                async for text in websocket:
                    try:
                        request = coordinator_frames.validate_json(text)
                    except ValidationError as error:
                        logger.error("lockstep: a request that is not one: %s", error.errors()[0]["msg"])
                        return
                    if isinstance(request, SettleFrame):
                        reply: ReportFrame | SteppedFrame = await self._settle(request)
                    else:
                        reply = self._step(request.id, request.what)
                    await websocket.send(reply.model_dump_json())

    async def _connect(self) -> ClientConnection | None:
        for _ in range(_CONNECT_TRIES):
            try:
                return await connect(self.url, open_timeout=2.0, max_size=None, compression=None)
            except (OSError, TimeoutError, InvalidHandshake, WebSocketException) as error:
                last = error
            await asyncio.sleep(_CONNECT_PAUSE_S)
        logger.error("lockstep: no coordinator at %s (%s); this process runs free", self.url, last)
        return None

    def _step(self, request_id: int, what: StepWhat) -> SteppedFrame:
        if self.stepper is None:
            raise RuntimeError("lockstep: a step was asked of a process that simulates nothing")
        time_s = self.stepper(what)
        _, counts = self._state()
        return SteppedFrame(id=request_id, time_s=time_s, nodes=_node_counts(counts))

    def _state(self) -> tuple[bool, Counts]:
        busy = ACTIVITY.busy()
        counts = []
        for node in self.nodes:
            node_busy, sent, received = node.lockstep_state()
            busy = busy or node_busy
            counts.append((node.get_name(), tuple(sent), tuple(received)))
        return busy, tuple(counts)

    async def _settle(self, request: SettleFrame) -> ReportFrame:
        loop = asyncio.get_running_loop()
        deadline = loop.time() + request.max_wait_s
        if request.expect or request.clock_s is not None:
            wanted = {(node.name, topic, peer): count for node in request.expect for topic, peer, count in node.received}
            settled, counts = await self._settled(deadline, lambda counts: _arrived(wanted, counts))
            if not settled:
                return self._report(request.id, False, counts)
            if request.clock_s is not None:
                for node in self.nodes:
                    node.lockstep_set_clock(request.clock_s)
        settled, counts = await self._settled(deadline, lambda _: True)
        return self._report(request.id, settled, counts)

    async def _settled(self, deadline: float, ready: Callable[[Counts], bool]) -> tuple[bool, Counts]:
        """Wait until the process is settled and ``ready(counts)``; (False, counts) at ``deadline``."""
        loop = asyncio.get_running_loop()
        turns = 0
        while True:
            busy, counts = self._state()
            if not busy and ready(counts):
                for _ in range(_CONFIRM_TURNS):
                    await asyncio.sleep(0)
                again_busy, again = self._state()
                if not again_busy and again == counts:
                    return True, counts
            if loop.time() > deadline:
                return False, counts
            turns += 1
            await asyncio.sleep(0 if turns < _SPIN_TURNS else _NAP_S)

    def _report(self, request_id: int, settled: bool, counts: Counts) -> ReportFrame:
        return ReportFrame(id=request_id, settled=settled, stepper=self.stepper is not None, nodes=_node_counts(counts))


def _node_counts(counts: Counts) -> list[NodeCounts]:
    return [
        NodeCounts(
            name=name,
            sent=list(sent),
            received=list(received),
        )
        for name, sent, received in counts
    ]


def _arrived(wanted: dict[tuple[str, str, str], int], counts: Counts) -> bool:
    """Whether every (node, topic, publisher) count in ``wanted`` has been received."""
    if not wanted:
        return True
    have = {(name, topic, peer): n for name, _, received in counts for topic, peer, n in received}
    return all(have.get(key, 0) >= count for key, count in wanted.items())


_agent: _Agent | None = None


def join(node: LockstepNode, url: str) -> None:
    """Add ``node`` (running, on the process's loop) to the process's lockstep run at ``url``."""
    global _agent
    if _agent is None:
        _agent = _Agent(url)
    _agent.nodes.append(node)
    _agent.start()


def set_stepper(stepper: Stepper) -> None:
    """Make this process the run's simulator: ``stepper`` answers the coordinator's steps (call
    it as soon as the simulator's node has joined: its reports say so from then on)."""
    if _agent is None or _agent._task is None:
        raise RuntimeError("lockstep: set the stepper once the simulator's node has joined")
    _agent.stepper = stepper


async def leave(node: LockstepNode) -> None:
    """Take ``node`` out of the run; the agent stops with the process's last node."""
    global _agent
    agent = _agent
    if agent is None or node not in agent.nodes:
        return
    agent.nodes.remove(node)
    if not agent.nodes:
        _agent = None
        await agent.stop()
