"""``rclpy.logging``: ``node.get_logger().info('text')`` and ``rclpy.logging.get_logger(name)``.

A node's logger prints the line (stderr, through Python's logging) and publishes it on
``/rosout`` from any thread. The rclpy keywords work: ``throttle_duration_sec``, ``once``,
``skip_first``. As in rclpy, a message is one string (format it yourself: f-strings).
"""

from __future__ import annotations

import logging as _logging
import threading
import time as _time
from enum import IntEnum
from typing import TYPE_CHECKING, Any

from services.runtime.logger import NODE_LOGGERS, NodeLogger
from shared_models.rcl_interfaces import Log

if TYPE_CHECKING:
    from services.runtime.node import Node as RuntimeNode

__all__ = [
    "LoggingSeverity",
    "RcutilsLogger",
    "get_logger",
    "get_logging_severity_from_string",
    "node_logger",
    "set_logger_level",
]


class LoggingSeverity(IntEnum):
    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


_TO_LOG = {
    LoggingSeverity.DEBUG: Log.DEBUG,
    LoggingSeverity.INFO: Log.INFO,
    LoggingSeverity.WARN: Log.WARN,
    LoggingSeverity.ERROR: Log.ERROR,
    LoggingSeverity.FATAL: Log.FATAL,
}
_TO_PYTHON = {
    LoggingSeverity.DEBUG: _logging.DEBUG,
    LoggingSeverity.INFO: _logging.INFO,
    LoggingSeverity.WARN: _logging.WARNING,
    LoggingSeverity.ERROR: _logging.ERROR,
    LoggingSeverity.FATAL: _logging.CRITICAL,
}


class RcutilsLogger:
    """rclpy's logger: ``debug``/``info``/``warning`` (``warn``)/``error``/``fatal``."""

    def __init__(self, name: str, node_logger: NodeLogger | None = None) -> None:
        self.name = name
        self._node_logger = node_logger
        self._python = _logging.getLogger(f"{NODE_LOGGERS}.{name.lstrip('/')}")
        self._level = LoggingSeverity.INFO
        self._lock = threading.Lock()
        self._seen: dict[tuple[str, int], dict[str, Any]] = {}

    def get_child(self, name: str) -> RcutilsLogger:
        return RcutilsLogger(f"{self.name}.{name}" if self.name else name, self._node_logger)

    def set_level(self, level: LoggingSeverity | int) -> None:
        self._level = LoggingSeverity(level)
        if self._node_logger is not None and self._level != LoggingSeverity.UNSET:
            self._node_logger.set_level(_TO_LOG[self._level])

    def get_effective_level(self) -> LoggingSeverity:
        return self._level

    def is_enabled_for(self, severity: LoggingSeverity | int) -> bool:
        return LoggingSeverity(severity) >= self._level

    def debug(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.DEBUG, **kwargs)

    def info(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.INFO, **kwargs)

    def warning(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.WARN, **kwargs)

    warn = warning

    def error(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.ERROR, **kwargs)

    def fatal(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.FATAL, **kwargs)

    def log(
        self, message: Any, severity: LoggingSeverity | int, *, throttle_duration_sec: float | None = None,
        throttle_time_source_type: Any = None, once: bool = False, skip_first: bool = False, **_: Any,
    ) -> bool:  # fmt: skip
        """Log ``message`` at ``severity``; whether it was logged (rclpy's filters may skip it)."""
        severity = LoggingSeverity(severity)
        if severity < self._level or not self._passes(severity, throttle_duration_sec, once, skip_first):
            return False
        text = str(message)
        if self._node_logger is not None:
            self._node_logger.log(_TO_LOG[severity], "%s", text, caller_depth=3)
        else:
            self._python.log(_TO_PYTHON[severity], "%s", text, stacklevel=3)
        return True

    def _passes(self, severity: LoggingSeverity, throttle_s: float | None, once: bool, skip_first: bool) -> bool:
        if throttle_s is None and not once and not skip_first:
            return True
        import sys

        caller = sys._getframe(3)
        key = (caller.f_code.co_filename, caller.f_lineno)  # each call site filters on its own
        with self._lock:
            seen = self._seen.setdefault(key, {"count": 0, "last": None})
            seen["count"] += 1
            if once and seen["count"] > 1:
                return False
            if skip_first and seen["count"] == 1:
                return False
            if throttle_s is not None:
                now = _time.monotonic()
                if seen["last"] is not None and now - seen["last"] < throttle_s:
                    return False
                seen["last"] = now
        return True


def node_logger(node: RuntimeNode, *, rosout: bool = True) -> RcutilsLogger:
    """The logger of an SDK node a façade made: it prints, and (with ``rosout``) publishes each
    line on /rosout from whatever thread logs it."""
    from services.ros.bridge import bridge

    publisher = node.rosout_publisher
    lines = NodeLogger(
        node.get_name(),
        lambda: node.get_clock().now().to_msg(),
        (lambda log: bridge.call_soon(publisher.publish, log)) if rosout else (lambda log: None),
        level=node.settings.log_level,
    )
    return RcutilsLogger(node.get_name().lstrip("/").replace("/", "."), lines)


_loggers: dict[str, RcutilsLogger] = {}


def get_logger(name: str) -> RcutilsLogger:
    """A logger of that name, not tied to a node (it prints; it does not publish on /rosout)."""
    if name not in _loggers:
        _loggers[name] = RcutilsLogger(name)
    return _loggers[name]


def set_logger_level(name: str, level: LoggingSeverity | int) -> None:
    get_logger(name).set_level(level)


def get_logging_severity_from_string(text: str) -> LoggingSeverity:
    return LoggingSeverity[text.upper()]
