"""``rospy.core``: the process's one node and its life (``is_shutdown``, ``signal_shutdown``,
``on_shutdown``), and the names it resolves.

A rospy process has at most one node, made by ``rospy.init_node``: here an SDK node
(:class:`services.runtime.Node`) on the bridge's loop. Shutdown is one-way, as in rospy: the
hooks run (once, in the order added), every sleep and ``spin`` ends, and the node leaves the
graph.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from services.ros.bridge import bridge
from services.ros.rclpy.logging import LoggingSeverity, RcutilsLogger, get_logger
from services.ros.rospy.exceptions import ROSInitException
from services.runtime.ros_args import NameResolver

if TYPE_CHECKING:
    from services.runtime.node import Node as RuntimeNode

__all__ = [
    "get_caller_id",
    "get_name",
    "get_namespace",
    "is_initialized",
    "is_shutdown",
    "is_shutdown_requested",
    "on_shutdown",
    "logger",
    "process",
    "report",
    "resolve_name",
    "signal_shutdown",
]

_UNNAMED = "unnamed"  # rospy's caller id before init_node


class RospyProcess:
    """This process's rospy state: its node (once ``init_node`` ran), shutdown and its hooks."""

    def __init__(self) -> None:
        self.node: RuntimeNode | None = None
        self.logger: RcutilsLogger | None = None
        self.init_arguments: tuple[Any, ...] | None = None
        self._lock = threading.Lock()
        self._shutdown = threading.Event()
        self._requested = False
        self.reason = ""
        self._hooks: list[Callable[..., Any]] = []

    def require_node(self, what: str) -> RuntimeNode:
        """The node, or ROSInitException naming ``what`` needed it."""
        if self.node is None:
            raise ROSInitException(f"{what} needs the node: call rospy.init_node('name') first")
        return self.node

    @property
    def names(self) -> NameResolver:
        """How this process's names resolve (the node's, or the root's before init_node)."""
        if self.node is not None:
            return self.node._names
        return NameResolver("/", _UNNAMED, [])

    def wait(self, timeout_s: float) -> bool:
        """Wait up to ``timeout_s`` for shutdown; whether it happened."""
        return self._shutdown.wait(timeout_s)

    def is_shutdown(self) -> bool:
        return self._shutdown.is_set()

    def shutdown(self, reason: str, *, stop_here: bool = True) -> None:
        """rospy's ``signal_shutdown``: run the hooks, end waits, and take the node out of the
        graph (in this thread if ``stop_here`` and it is the main thread; else in a thread of
        its own, since the caller may be a callback the node's stop waits for, or a signal
        handler that interrupted the bridge itself)."""
        with self._lock:
            if self._requested:
                return
            self._requested = True
            self.reason = reason
            hooks, self._hooks = self._hooks, []
        if self.logger is not None:
            self.logger.info(f"signal_shutdown [{reason}]")
        for hook in hooks:
            _call_hook(hook, reason)
        self._shutdown.set()
        if stop_here and threading.current_thread() is threading.main_thread():
            bridge.shutdown()
        else:
            threading.Thread(target=bridge.shutdown, name="rospy shutdown", daemon=True).start()

    def add_hook(self, hook: Callable[..., Any]) -> None:
        with self._lock:
            if not self._requested:
                self._hooks.append(hook)
                return
        _call_hook(hook, self.reason)  # after shutdown, rospy calls a new hook at once

    def requested(self) -> bool:
        return self._requested


def _call_hook(hook: Callable[..., Any], reason: str) -> None:
    import inspect

    try:
        parameters = inspect.signature(hook).parameters
        takes_reason = any(p.default is inspect.Parameter.empty for p in parameters.values()) or any(
            p.kind is inspect.Parameter.VAR_POSITIONAL for p in parameters.values()
        )
    except (TypeError, ValueError):
        takes_reason = False
    try:
        hook(reason) if takes_reason else hook()
    except Exception as error:  # one hook's failure must not stop the others
        report(error, f"the shutdown hook {getattr(hook, '__qualname__', hook)}")


process = RospyProcess()
"""The process's rospy state."""


def is_initialized() -> bool:
    """Whether ``init_node`` has run."""
    return process.node is not None


def is_shutdown() -> bool:
    """Whether the node is shutting down (the main loop's condition)."""
    return process.is_shutdown()


def is_shutdown_requested() -> bool:
    """Whether a shutdown was asked for (it may be under way)."""
    return process.requested()


def signal_shutdown(reason: str) -> None:
    """Shut the node down: hooks run, sleeps end, ``is_shutdown()`` turns True."""
    process.shutdown(reason)


def on_shutdown(h: Callable[..., Any]) -> None:
    """Call ``h()`` when the node shuts down (``h(reason)`` if it takes an argument)."""
    if not callable(h):
        raise TypeError(f"on_shutdown takes a function, got {h!r}")
    process.add_hook(h)


def get_name() -> str:
    """The node's full name (``/perception``); ``/unnamed`` before ``init_node``."""
    return process.names.full_node_name


get_caller_id = get_name


def get_namespace() -> str:
    """The node's namespace, ending with ``/`` as rospy's does (``/`` or ``/robot1/``)."""
    namespace = process.names.namespace
    return namespace if namespace.endswith("/") else namespace + "/"


def resolve_name(name: str, caller_id: str | None = None) -> str:
    """``name`` as the graph knows it: relative names in the node's namespace, ``~name`` under
    the node's name, then the node's remappings."""
    if caller_id is not None:
        namespace, _, node = caller_id.rpartition("/")
        return NameResolver(namespace or "/", node, []).resolve(name)
    return process.names.resolve(name)


def logger() -> RcutilsLogger:
    """Where rospy's lines go: the node's logger (printed and on ``/rosout``), or before
    ``init_node`` a logger that only prints, as rospy's does."""
    if process.logger is not None:
        return process.logger
    from services.runtime.executor import configure_logging

    configure_logging()
    return get_logger("rospy")


def report(error: BaseException, what: str) -> None:
    """A user callback raised: their traceback (their file and line), and the node keeps running."""
    from services.ros.tracebacks import user_traceback

    logger().log(f"{what} raised (the node keeps running):\n{user_traceback(error)}", LoggingSeverity.ERROR)
