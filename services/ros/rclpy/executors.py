"""``rclpy.executors``: where callbacks run. ``rclpy.spin(node)`` uses the global
SingleThreadedExecutor; a MultiThreadedExecutor runs callbacks on a pool of threads, callback
groups deciding which may overlap.

Unlike rclpy, a callback may block on a service call (``client.call``) or a ``Rate`` even under
a SingleThreadedExecutor: responses and clocks are served by the bridge's loop, not by the
executor, so nothing deadlocks. An exception in a callback prints the user's traceback and the
node keeps running (rclpy would end ``spin`` with it).
"""

from __future__ import annotations

import os
import queue
import threading
import time
from typing import TYPE_CHECKING, Any

from services.ros.errors import RosFacadeError
from services.ros.pacing import thread_waits_for_work
from services.ros.rclpy.context import Context, default_context
from services.ros.rclpy.task import Future
from services.ros.rclpy.waitable import Job, Waitable
from services.runtime.lockstep.activity import ACTIVITY

if TYPE_CHECKING:
    from services.ros.rclpy.node import Node

__all__ = [
    "Executor",
    "ExternalShutdownException",
    "MultiThreadedExecutor",
    "ShutdownException",
    "SingleThreadedExecutor",
    "TimeoutException",
    "get_global_executor",
]

_IDLE_WAKE_S = 0.1  # how often an idle wait looks at ok() and the executor's shutdown again


class ExternalShutdownException(RosFacadeError):
    """rclpy was shut down (from another thread) while an executor spun."""


class ShutdownException(RosFacadeError):
    """The executor was shut down."""


class TimeoutException(RosFacadeError):
    """A wait of the executor timed out."""


class Executor:
    """Runs the callbacks of the nodes added to it (``add_node``), in the calling thread."""

    def __init__(self, *, context: Context | None = None) -> None:
        self._context = context or default_context
        self._nodes: list[Node] = []
        self._nodes_lock = threading.Lock()
        self._ready: queue.SimpleQueue[Waitable | None] = queue.SimpleQueue()
        self._is_shutdown = False
        self._deferred: list[Waitable] = []  # ready, but their callback group was busy

    @property
    def context(self) -> Context:
        return self._context

    # -- nodes --------------------------------------------------------------------------------

    def add_node(self, node: Node) -> bool:
        """Run ``node``'s callbacks here; False if it already is. A node has one executor."""
        with self._nodes_lock:
            if node in self._nodes:
                return False
            self._nodes.append(node)
        node._rclpy_set_executor(self)
        for entity in node._rclpy_waitables():
            if entity._has_work():
                self._notify(entity)
        return True

    def remove_node(self, node: Node) -> None:
        with self._nodes_lock:
            if node not in self._nodes:
                return
            self._nodes.remove(node)
        node._rclpy_set_executor(None)  # a spin of nothing left ends within _IDLE_WAKE_S

    def get_nodes(self) -> list[Node]:
        with self._nodes_lock:
            return list(self._nodes)

    # -- waking -------------------------------------------------------------------------------

    def _notify(self, entity: Waitable) -> None:
        self._ready.put(entity)

    def wake(self) -> None:
        """Make a waiting ``spin_once`` look again."""
        self._ready.put(None)

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Stop spinning and let go of every node."""
        self._is_shutdown = True
        for node in self.get_nodes():
            self.remove_node(node)
        return True

    def _spinning(self) -> bool:
        return self._context.ok() and not self._is_shutdown

    # -- spinning -----------------------------------------------------------------------------

    def spin(self) -> None:
        """Run callbacks until rclpy shuts down, this executor does, or its nodes are gone."""
        while self._spinning() and self.get_nodes():
            self.spin_once(timeout_sec=_IDLE_WAKE_S)

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Run at most one callback, waiting up to ``timeout_sec`` (None: until one is ready)."""
        ready = self._next(timeout_sec)
        if ready is not None:
            self._run(*ready)

    def spin_until_future_complete(self, future: Future, timeout_sec: float | None = None) -> None:
        """Run callbacks until ``future`` is done, or ``timeout_sec`` passes."""
        future._add_waker(self.wake)
        deadline = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while self._spinning() and not future.done():
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                return
            self.spin_once(timeout_sec=left)

    def spin_once_until_future_complete(self, future: Future, timeout_sec: float | None = None) -> None:
        future._add_waker(self.wake)
        self.spin_once(timeout_sec)

    def _next(self, timeout_sec: float | None) -> tuple[Waitable, Job] | None:
        """The next (entity, job) whose callback group lets it start; None when time is up."""
        deadline = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        thread_waits_for_work()
        while self._spinning():
            left = _IDLE_WAKE_S if deadline is None else min(_IDLE_WAKE_S, deadline - time.monotonic())
            if left < 0:
                return None
            try:
                entity = self._ready.get(timeout=left)
            except queue.Empty:
                if deadline is not None and time.monotonic() >= deadline:
                    return None
                continue
            if entity is None:
                return None  # woken: the caller looks at its condition again (a future, shutdown)
            if entity._node not in self.get_nodes():
                continue  # its node left this executor; the work waits in the entity
            group = entity.callback_group
            if group is not None and not group.beginning(entity):
                with self._nodes_lock:
                    self._deferred.append(entity)
                continue
            job = entity._take()
            if job is not None:
                return entity, job
            if group is not None:
                self._ended(group)
        return None

    def _run(self, entity: Waitable, job: Job) -> None:
        ACTIVITY.begin()  # a lockstep run waits for the callback
        try:
            job()
        except Exception as error:
            entity._node._rclpy_report(error, entity.what)
        finally:
            ACTIVITY.end()
            if entity.callback_group is not None:
                self._ended(entity.callback_group)

    def _ended(self, group: Any) -> None:
        group.ending()
        with self._nodes_lock:
            waiting = [e for e in self._deferred if e.callback_group is group]
            self._deferred = [e for e in self._deferred if e.callback_group is not group]
        for entity in waiting:
            self._notify(entity)


class SingleThreadedExecutor(Executor):
    """One callback at a time, in the thread that spins."""


class MultiThreadedExecutor(Executor):
    """Callbacks on ``num_threads`` threads (default: the CPU count, at least 2); callbacks of
    one MutuallyExclusiveCallbackGroup never overlap, those of a ReentrantCallbackGroup may."""

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        self._num_threads = num_threads or max(os.cpu_count() or 2, 2)
        if self._num_threads < 1:
            raise ValueError("num_threads must be at least 1")

    def spin_once(self, timeout_sec: float | None = None) -> None:
        ready = self._next(timeout_sec)
        if ready is not None:
            threading.Thread(target=self._run, args=ready, daemon=True).start()

    def spin(self) -> None:
        workers = [
            threading.Thread(target=self._work, name=f"rclpy executor {i}", daemon=True)
            for i in range(self._num_threads)
        ]
        for worker in workers:
            worker.start()
        try:
            while self._spinning() and self.get_nodes():
                time.sleep(_IDLE_WAKE_S)  # Ctrl-C reaches the main thread here
        finally:
            stop = self._is_shutdown
            self._is_shutdown = True
            for _ in workers:
                self.wake()
            for worker in workers:
                worker.join(1.0)
            self._is_shutdown = stop

    def _work(self) -> None:
        while self._spinning() and self.get_nodes():
            ready = self._next(_IDLE_WAKE_S)
            if ready is not None:
                self._run(*ready)


_global_executor: Executor | None = None
_global_lock = threading.Lock()


def get_global_executor() -> Executor:
    """The executor ``rclpy.spin`` uses (a SingleThreadedExecutor)."""
    global _global_executor
    with _global_lock:
        if _global_executor is None:
            _global_executor = SingleThreadedExecutor()
        return _global_executor

