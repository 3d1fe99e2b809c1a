"""One node of a launch as the supervisor keeps it: its plan, its current process, where it is in
its life (:class:`NodeState`) and what :meth:`Supervisor.status` shows of it (:class:`NodeStatus`)."""

from __future__ import annotations

import asyncio
import enum
from collections import deque
from dataclasses import dataclass

from services.launch.child_process import ChildProcess
from services.launch.plan import NodePlan

__all__ = ["BACKOFF_FIRST_S", "BACKOFF_MAX_S", "BACKOFF_RESET_AFTER_S", "LaunchedNode", "NodeState", "NodeStatus"]

# -- respawn ------------------------------------------------------------------------------------
BACKOFF_FIRST_S = 0.5
BACKOFF_MAX_S = 8.0
BACKOFF_RESET_AFTER_S = 30.0
"""A node that ran this long before dying is respawned after the first backoff again."""
# -- output -------------------------------------------------------------------------------------
_STDERR_TAIL_LINES = 20


class NodeState(enum.Enum):
    """Where a node is in its life under the supervisor."""

    WAITING = "waiting"  # not started yet
    STARTING = "starting"  # running, not answering /health yet
    READY = "ready"
    BACKOFF = "backoff"  # died; respawning after a pause
    EXITED = "exited"  # died and is not respawned
    KILLED = "killed"  # stopped on request (`skydeck node kill`); not respawned
    STOPPED = "stopped"  # stopped by the supervisor


@dataclass(frozen=True)
class NodeStatus:
    """A snapshot of one node: ``ready_count`` counts how often it has become ready."""

    name: str
    url: str
    state: NodeState
    pid: int | None
    ready_count: int
    restarts: int
    exit_code: int | None


class LaunchedNode:
    """The supervisor's record of one node and its current process."""

    def __init__(self, plan: NodePlan) -> None:
        self.plan = plan
        self.state = NodeState.WAITING
        self.process: ChildProcess | None = None
        self.pid: int | None = None
        self.watch: asyncio.Task[None] | None = None
        self.started_at = 0.0
        self.starts = 0
        self.ready_count = 0
        self.exit_code: int | None = None
        self.backoff_s = BACKOFF_FIRST_S
        self.kill_requested = False
        self.stderr_tail: deque[str] = deque(maxlen=_STDERR_TAIL_LINES)

    @property
    def exited(self) -> asyncio.Future[int] | None:
        return self.process.exited if self.process else None

    @property
    def running(self) -> bool:
        return self.process is not None and self.process.running

    def status(self) -> NodeStatus:
        """A snapshot of the node."""
        return NodeStatus(
            name=self.plan.name,
            url=self.plan.url,
            state=self.state,
            pid=self.pid if self.running else None,
            ready_count=self.ready_count,
            restarts=max(self.starts - 1, 0),
            exit_code=self.exit_code,
        )
