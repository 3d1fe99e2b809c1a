"""``rclpy.context.Context``: whether rclpy is initialised (``rclpy.init()`` .. ``rclpy.shutdown()``).

``init`` reads the program's ROS arguments, starts logging to stderr, and makes SIGTERM end the
program as Ctrl-C does (so its ``finally:`` blocks run and its nodes leave the graph).
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable
from typing import Any

from services.ros.errors import RosFacadeError

__all__ = ["Context", "NotInitializedException", "default_context"]


class NotInitializedException(RosFacadeError, RuntimeError):
    """rclpy was used before ``rclpy.init()`` (or after ``rclpy.shutdown()``)."""


class Context:
    """The state ``rclpy.ok()`` reports; one per process (``default_context``) unless made."""

    def __init__(self) -> None:
        self._ok = False
        self._lock = threading.Lock()
        self._callbacks: list[Callable[[], Any]] = []

    def init(self, args: list[str] | None = None, *, initialize_logging: bool = True) -> None:
        from services.runtime.executor import configure_logging
        from services.runtime.ros_args import (
            ROS_ARGS,
            parse_ros_args,
            set_process_ros_arguments,
            split_ros_args,
        )

        with self._lock:
            if self._ok:
                raise RuntimeError("Context.init() must only be called once")
            if args is not None and ROS_ARGS in args:  # the program's own list: its --ros-args
                set_process_ros_arguments(parse_ros_args(split_ros_args(list(args))[1]))
            if initialize_logging:
                configure_logging()
            _end_on_sigterm()
            self._ok = True

    def ok(self) -> bool:
        return self._ok

    def shutdown(self) -> None:
        """End: ``ok()`` turns False, spins return, this process's nodes leave the graph."""
        from services.ros.bridge import bridge

        with self._lock:
            if not self._ok:
                return  # rclpy raises here; a second shutdown is harmless (as try_shutdown)
            self._ok = False
            callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback()
        bridge.shutdown()

    try_shutdown = shutdown

    def on_shutdown(self, callback: Callable[[], Any]) -> None:
        """Call ``callback()`` when this context shuts down."""
        with self._lock:
            self._callbacks.append(callback)

    def check(self, what: str) -> None:
        if not self._ok:
            raise NotInitializedException(f"rclpy.init() must be called before {what}")


def _end_on_sigterm() -> None:
    """SIGTERM (`skydeck launch`, `docker stop`) ends the program as Ctrl-C does."""
    if threading.current_thread() is threading.main_thread() and signal.getsignal(signal.SIGTERM) is signal.SIG_DFL:
        signal.signal(signal.SIGTERM, signal.default_int_handler)


default_context = Context()
