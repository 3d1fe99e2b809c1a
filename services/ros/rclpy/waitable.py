"""What an executor runs: entities (subscriptions, timers, services, a node's loose jobs) that
the bridge's loop marks ready, and that hand the executor one job at a time.

The loop thread only records work (a message into the subscription's queue, a timer's tick) and
tells the executor the node is added to, if any; the user's callback runs where the program spins
(``rclpy.spin``, an executor's threads). Work waits in the entity while no executor spins its
node, as ROS's middleware holds messages until ``spin``.
"""

from __future__ import annotations

import collections
import inspect
import threading
from collections.abc import Callable
from typing import Any, Protocol

from services.ros.rclpy.callback_groups import CallbackGroup
from services.ros.rclpy.logging import RcutilsLogger

__all__ = ["JobQueue", "Owner", "Waitable", "run_callback"]

Job = Callable[[], Any]


class Owner(Protocol):
    """The node an entity belongs to, as its entities see it (:class:`rclpy.node.Node` is one):
    a type of its own so that the entities' modules need not import the node's, which imports them."""

    _rclpy_executor: Any  # the executor spinning the node, if one does

    def _rclpy_dispatch(self, job: Job) -> None: ...

    def _rclpy_report(self, error: BaseException, what: str) -> None: ...

    def get_logger(self) -> RcutilsLogger: ...


class Waitable:
    """An entity of a node with callbacks to run (see the module docstring)."""

    what = "callback"

    def __init__(self, node: Owner, callback_group: CallbackGroup | None) -> None:
        self._node = node
        self.callback_group = callback_group

    def _notify(self) -> None:
        """Called from any thread when work arrives."""
        executor = self._node._rclpy_executor
        if executor is not None:
            executor._notify(self)

    def _has_work(self) -> bool:
        raise NotImplementedError

    def _take(self) -> Job | None:
        """The next job, or None when there is none (any more)."""
        raise NotImplementedError


class JobQueue(Waitable):
    """Callables to run in the executor: service requests, done callbacks of futures."""

    def __init__(self, node: Owner, callback_group: CallbackGroup | None, what: str) -> None:
        super().__init__(node, callback_group)
        self.what = what
        self._jobs: collections.deque[Job] = collections.deque()
        self._lock = threading.Lock()

    def put(self, job: Job) -> None:
        with self._lock:
            self._jobs.append(job)
        self._notify()

    def _has_work(self) -> bool:
        return bool(self._jobs)

    def _take(self) -> Job | None:
        with self._lock:
            return self._jobs.popleft() if self._jobs else None


def run_callback(callback: Callable[..., Any], *args: Any) -> Any:
    """Call a user callback; an ``async def`` one is driven to its end here, waiting in this
    thread for each rclpy Future it awaits (the bridge's loop completes them)."""
    result = callback(*args)
    if not inspect.iscoroutine(result):
        return result
    from services.ros.rclpy.task import Future

    value: Any = None
    while True:
        try:
            yielded = result.send(value)
        except StopIteration as stop:
            return stop.value
        if isinstance(yielded, Future):
            yielded.wait()
        value = None
