"""``rclpy.callback_groups``: which callbacks may run at the same time under a
MultiThreadedExecutor. A node's callbacks share its default MutuallyExclusiveCallbackGroup
unless given another; a SingleThreadedExecutor runs one callback at a time anyway."""

from __future__ import annotations

import threading

__all__ = ["CallbackGroup", "MutuallyExclusiveCallbackGroup", "ReentrantCallbackGroup"]


class CallbackGroup:
    """The base: :meth:`beginning` says whether a callback of the group may start now."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._running = 0

    def can_execute(self, entity: object = None) -> bool:
        with self._lock:
            return self._allows(self._running)

    def beginning(self, entity: object = None) -> bool:
        """Claim a slot for one callback; False if the group must wait."""
        with self._lock:
            if not self._allows(self._running):
                return False
            self._running += 1
            return True

    def ending(self, entity: object = None) -> None:
        with self._lock:
            self._running -= 1

    def _allows(self, running: int) -> bool:
        raise NotImplementedError


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One callback of the group at a time."""

    def _allows(self, running: int) -> bool:
        return running == 0


class ReentrantCallbackGroup(CallbackGroup):
    """Any number at once (even the same callback twice)."""

    def _allows(self, running: int) -> bool:
        return True
