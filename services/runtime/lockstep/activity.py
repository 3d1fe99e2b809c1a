"""What a process is doing that a lockstep run must wait for (:mod:`services.runtime.lockstep`).

Two kinds of work are counted here, from any thread:

- work with a start and an end, counted while it runs (``with ACTIVITY.working():``): an HTTP
  request out (a service call), a service's handler, a job a ROS façade runs on its own thread;
- work that waits in a queue the runtime does not own (a rospy subscriber's thread, an rclpy
  executor's entities, a ROS ``Rate`` woken by sim time): its owner registers a *probe*, a
  function that says whether it has work now.

A node's own subscriptions and timers are asked directly (``Node.lockstep_busy``). Counting
costs an addition under a lock; a process that is not in a lockstep run counts all the same
(nobody asks), which is cheaper than asking whether it is at every call.
"""

from __future__ import annotations

import contextlib
import threading
import weakref
from collections.abc import Callable, Iterator

__all__ = ["ACTIVITY", "Activity"]

Probe = Callable[[], bool]


class Activity:
    """Work in progress in this process: a count, and probes of queues held elsewhere."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._running = 0
        self._probes: weakref.WeakKeyDictionary[object, Probe] = weakref.WeakKeyDictionary()

    def begin(self) -> None:
        """A piece of work started (pair it with :meth:`end`)."""
        with self._lock:
            self._running += 1

    def end(self) -> None:
        """A piece of work ended."""
        with self._lock:
            self._running -= 1

    @contextlib.contextmanager
    def working(self) -> Iterator[None]:
        """Count the block as work in progress."""
        self.begin()
        try:
            yield
        finally:
            self.end()

    def watch(self, owner: object, probe: Probe) -> None:
        """Ask ``probe()`` whether ``owner`` has work, for as long as ``owner`` lives."""
        with self._lock:
            self._probes[owner] = probe

    def unwatch(self, owner: object) -> None:
        with self._lock:
            self._probes.pop(owner, None)

    def busy(self) -> bool:
        """Whether any counted work runs or any probe says its owner has work."""
        with self._lock:
            if self._running:
                return True
            probes = list(self._probes.values())
        return any(probe() for probe in probes)


ACTIVITY = Activity()
"""This process's activity."""
