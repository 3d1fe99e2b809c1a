"""rospy's logging: ``rospy.loginfo("Got %s boxes", n)``, ``logwarn``, ``logerr``, ``logdebug``,
``logfatal``, and their ``_throttle(period, ...)`` and ``_once(...)`` forms.

Arguments are %-formatted as rospy does (``msg % args`` when there are any). Once the node
exists, each line is printed and published on ``/rosout`` (from any thread), as rospy's are;
before ``init_node`` it is only printed. The filtering (``_throttle``, ``_once``: per call
site) and the printing are the rclpy façade's logger's (:mod:`services.ros.rclpy.logging`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from services.ros.rclpy.logging import LoggingSeverity
from services.ros.rospy.core import logger

__all__ = [  # rospy's own names (what `from rospy import *` has of this module)
    "DEBUG",
    "ERROR",
    "FATAL",
    "INFO",
    "WARN",
    "logdebug",
    "logdebug_once",
    "logdebug_throttle",
    "logerr",
    "logerr_once",
    "logerr_throttle",
    "logfatal",
    "logfatal_once",
    "logfatal_throttle",
    "loginfo",
    "loginfo_once",
    "loginfo_throttle",
    "logout",
    "logwarn",
    "logwarn_once",
    "logwarn_throttle",
]

# rospy's log levels (rosgraph_msgs/Log's constants), as init_node(log_level=...) takes them.
DEBUG, INFO, WARN, ERROR, FATAL = 1, 2, 4, 8, 16
_SEVERITY = {
    DEBUG: LoggingSeverity.DEBUG,
    INFO: LoggingSeverity.INFO,
    WARN: LoggingSeverity.WARN,
    ERROR: LoggingSeverity.ERROR,
    FATAL: LoggingSeverity.FATAL,
}


def severity(level: int) -> LoggingSeverity:
    """rospy's level (``rospy.DEBUG``...) as the logger's severity."""
    try:
        return _SEVERITY[level]
    except KeyError:
        raise ValueError(f"log_level must be rospy.DEBUG, INFO, WARN, ERROR or FATAL, got {level!r}") from None


def _text(msg: Any, args: tuple[Any, ...]) -> str:
    return str(msg) % args if args else str(msg)


# Each function made here calls the logger's `log` itself, so that the logger sees the user's
# line three frames up (what `_throttle`/`_once` key on, and what /rosout names as the place).
def _every_time(level: LoggingSeverity) -> Callable[..., None]:
    def log(msg: Any, *args: Any, **kwargs: Any) -> None:
        logger().log(_text(msg, args), level)

    log.__doc__ = f"Log at {level.name}: ``msg % args`` (rospy's form: ``loginfo('got %s', n)``)."
    return log


def _throttled(level: LoggingSeverity) -> Callable[..., None]:
    def log(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
        logger().log(_text(msg, args), level, throttle_duration_sec=period)

    log.__doc__ = f"Log at {level.name} at most once every ``period`` seconds from this line."
    return log


def _once(level: LoggingSeverity) -> Callable[..., None]:
    def log(msg: Any, *args: Any, **kwargs: Any) -> None:
        logger().log(_text(msg, args), level, once=True)

    log.__doc__ = f"Log at {level.name} the first time this line runs only."
    return log


logdebug = _every_time(LoggingSeverity.DEBUG)
loginfo = _every_time(LoggingSeverity.INFO)
logwarn = _every_time(LoggingSeverity.WARN)
logerr = _every_time(LoggingSeverity.ERROR)
logfatal = _every_time(LoggingSeverity.FATAL)
logout = loginfo
logdebug_throttle = _throttled(LoggingSeverity.DEBUG)
loginfo_throttle = _throttled(LoggingSeverity.INFO)
logwarn_throttle = _throttled(LoggingSeverity.WARN)
logerr_throttle = _throttled(LoggingSeverity.ERROR)
logfatal_throttle = _throttled(LoggingSeverity.FATAL)
logdebug_once = _once(LoggingSeverity.DEBUG)
loginfo_once = _once(LoggingSeverity.INFO)
logwarn_once = _once(LoggingSeverity.WARN)
logerr_once = _once(LoggingSeverity.ERROR)
logfatal_once = _once(LoggingSeverity.FATAL)

