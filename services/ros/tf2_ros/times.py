"""The times and durations tf2's API takes, from either client library, as integer nanoseconds.

- a time: ``rclpy.time.Time`` (``Time()`` is 0: the latest), a ``builtin_interfaces/msg/Time``
  (a header's stamp; ``rospy.Time(0)`` is one);
- a timeout or cache time: ``rclpy.duration.Duration``, ``builtin_interfaces/msg/Duration``
  (``rospy.Duration``), or seconds as a number; None is none.
"""

from __future__ import annotations

from typing import Any

from services.ros.pacing import S_TO_NS
from services.ros.rclpy.duration import Duration as RclpyDuration
from services.ros.rclpy.time import Time as RclpyTime
from services.ros.tf2_ros.exceptions import InvalidArgumentException
from shared_models.builtin_interfaces import Duration as DurationMsg
from shared_models.builtin_interfaces import Time as TimeMsg

__all__ = ["LATEST", "duration_ns", "format_time", "stamp", "time_ns"]

LATEST = 0
"""Time zero asks for the latest transform the frames have in common."""


def time_ns(time: Any, what: str = "time") -> int:
    """``time`` in nanoseconds (0: the latest)."""
    if isinstance(time, RclpyTime):  # first: isinstance on a message class is the slower check
        return time.nanoseconds
    if isinstance(time, TimeMsg):
        return int(time.to_nsec())
    raise InvalidArgumentException(
        f"{what} must be an rclpy.time.Time, a rospy.Time or a header's stamp "
        f"(Time() for the latest), got {type(time).__name__} {time!r}"
    )


def duration_ns(duration: Any, what: str = "timeout") -> int:
    """``duration`` in nanoseconds (None: 0)."""
    if duration is None:
        return 0
    if isinstance(duration, DurationMsg):
        return int(duration.to_nsec())
    if isinstance(duration, RclpyDuration):
        return duration.nanoseconds
    if isinstance(duration, int | float) and not isinstance(duration, bool):
        return int(duration * S_TO_NS)
    raise InvalidArgumentException(
        f"{what} must be an rclpy.duration.Duration, a rospy.Duration or seconds, got {type(duration).__name__} {duration!r}"
    )


def stamp(nanoseconds: int) -> TimeMsg:
    """A ``builtin_interfaces/msg/Time`` (a transform's ``header.stamp``)."""
    return TimeMsg.from_nsec(nanoseconds)  # type: ignore[no-any-return]


def format_time(nanoseconds: int) -> str:
    """As tf2 prints times in its messages (seconds, six decimals)."""
    return f"{nanoseconds / S_TO_NS:.6f}"
