"""A node's logger: Python ``logging`` plus a ``rcl_interfaces/msg/Log`` on ``/rosout``."""

from __future__ import annotations

import logging
import sys
from collections.abc import Callable
from typing import Any

from shared_models.builtin_interfaces import Time
from shared_models.rcl_interfaces import Log

__all__ = ["NODE_LOGGERS", "NodeLogger", "RosLogFormatter", "ros_logger_name"]

NODE_LOGGERS = "skydeck.node"
"""The parent of every node's Python logger (``skydeck.node.talker``), one logger tree for all."""

_LEVELS = {
    Log.DEBUG: logging.DEBUG,
    Log.INFO: logging.INFO,
    Log.WARN: logging.WARNING,
    Log.ERROR: logging.ERROR,
    Log.FATAL: logging.CRITICAL,
}


def ros_logger_name(python_name: str) -> str:
    """The name ROS prints for a Python logger: a node's is its node's logger name, as rclpy's
    (``skydeck.node.talker`` -> ``talker``; in a namespace, ``robot1.wall_follower``); any other
    logger keeps its own (``uvicorn.error``)."""
    prefix = NODE_LOGGERS + "."
    if not python_name.startswith(prefix):
        return python_name
    return python_name.removeprefix(prefix).replace("/", ".")


class RosLogFormatter(logging.Formatter):
    """``[INFO] [talker]: message``: ROS 2's console line (without its time), named as ROS names
    the logger."""

    def __init__(self) -> None:
        super().__init__("[%(levelname)s] [%(ros_name)s]: %(message)s")

    def formatMessage(self, record: logging.LogRecord) -> str:
        record.ros_name = ros_logger_name(record.name)
        return super().formatMessage(record)


class NodeLogger:
    """What ``node.get_logger()`` returns: ``info``, ``warn``, ``error``... as in rclpy and rospy.

    Messages may use %-style arguments as rospy's ``loginfo("got %s", x)`` does.
    """

    def __init__(
        self, node_name: str, stamp: Callable[[], Time], publish: Callable[[Log], None], *, level: str = "INFO"
    ) -> None:
        self.name = node_name
        # The node's own threshold (ROS's logger level) decides what reaches /rosout, whatever
        # the process's logging configuration does with the local copy.
        self._min_python_level = logging.getLevelName(level.upper())
        if not isinstance(self._min_python_level, int):
            raise ValueError(f"unknown log level {level!r}: use debug, info, warning or error")
        self._logger = logging.getLogger(f"{NODE_LOGGERS}.{node_name.lstrip('/')}")
        self._stamp = stamp
        self._publish = publish

    @property
    def logger(self) -> logging.Logger:
        """The underlying ``logging`` logger (for ``exception()`` and handlers)."""
        return self._logger

    def debug(self, msg: str, *args: Any) -> None:
        self._log(Log.DEBUG, msg, args)

    def info(self, msg: str, *args: Any) -> None:
        self._log(Log.INFO, msg, args)

    def warning(self, msg: str, *args: Any) -> None:
        self._log(Log.WARN, msg, args)

    warn = warning

    def error(self, msg: str, *args: Any) -> None:
        self._log(Log.ERROR, msg, args)

    def fatal(self, msg: str, *args: Any) -> None:
        self._log(Log.FATAL, msg, args)

    def _log(self, level: int, msg: str, args: tuple[Any, ...]) -> None:
        self.log(level, msg, *args, caller_depth=3)

    def is_enabled_for(self, level: int) -> bool:
        """Whether a line of ``level`` (``Log.INFO``...) would be logged."""
        return _LEVELS[level] >= self._min_python_level

    def set_level(self, level: int) -> None:
        """Log lines of ``level`` (``Log.INFO``...) and above from now on."""
        self._min_python_level = _LEVELS[level]

    def log(self, level: int, msg: str, *args: Any, caller_depth: int = 1) -> None:
        """Log ``msg`` at ``level`` (``Log.INFO``...); the /rosout line names the code
        ``caller_depth`` frames up as where it was logged (1: whoever called this)."""
        python_level = _LEVELS[level]
        if python_level < self._min_python_level:
            return
        text = str(msg) % args if args else str(msg)
        caller = sys._getframe(caller_depth)
        self._logger.log(python_level, "%s", text)
        self._publish(
            Log(
                stamp=self._stamp(),
                level=level,
                name=self.name,
                msg=text,
                file=caller.f_code.co_filename,
                function=caller.f_code.co_name,
                line=caller.f_lineno,
            )
        )
