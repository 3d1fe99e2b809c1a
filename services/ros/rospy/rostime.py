"""``rospy.Time`` and ``rospy.Duration``, and ROS time: ``rospy.Time.now()``, ``get_time()``.

    start = rospy.Time.now()
    if rospy.Time.now() - start > rospy.Duration(2): ...
    msg.header.stamp = rospy.Time.now()

They are ``builtin_interfaces`` Time and Duration (``shared_models``: ``Time(secs, nsecs)``,
``to_sec()``, ``from_sec()``, ``secs``/``nsecs``, arithmetic and ordering as genpy's), so a
``rospy.Time`` goes into a header's stamp as it is and compares with a received one; arithmetic
on them gives rospy's types back. ROS time is the node's clock: the simulator's ``/clock`` when
the ``/use_sim_time`` parameter is set, the wall clock otherwise (and before ``init_node``).
"""

from __future__ import annotations

import time as _time
from typing import Any

from services.ros.rospy.core import process
from shared_models.builtin_interfaces import Duration as DurationMsg
from shared_models.builtin_interfaces import Time as TimeMsg

__all__ = ["Duration", "Time", "get_rostime", "get_time", "is_wallclock", "now_ns"]


class Duration(DurationMsg):
    """rospy's Duration: ``Duration(secs, nsecs)``, ``Duration(1.5)``, ``Duration.from_sec(x)``."""

    def __add__(self, other: object) -> Any:
        if isinstance(other, TimeMsg):
            return Time.from_nsec(self.to_nsec() + other.to_nsec())
        if isinstance(other, DurationMsg):
            return Duration.from_nsec(self.to_nsec() + other.to_nsec())
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if isinstance(other, DurationMsg):
            return Duration.from_nsec(self.to_nsec() - other.to_nsec())
        return NotImplemented

    def __rsub__(self, other: object) -> Any:
        if isinstance(other, TimeMsg):
            return Time.from_nsec(other.to_nsec() - self.to_nsec())
        if isinstance(other, DurationMsg):
            return Duration.from_nsec(other.to_nsec() - self.to_nsec())
        return NotImplemented

    def __neg__(self) -> Duration:
        return Duration.from_nsec(-self.to_nsec())  # type: ignore[no-any-return]

    def __abs__(self) -> Duration:
        return Duration.from_nsec(abs(self.to_nsec()))  # type: ignore[no-any-return]

    def __mul__(self, factor: object) -> Any:
        result = super().__mul__(factor)
        return result if result is NotImplemented else Duration.from_nsec(result.to_nsec())

    __rmul__ = __mul__

    def __truediv__(self, divisor: object) -> Any:
        result = super().__truediv__(divisor)
        return Duration.from_nsec(result.to_nsec()) if isinstance(result, DurationMsg) else result

    def __floordiv__(self, divisor: object) -> Any:
        if isinstance(divisor, DurationMsg):
            return self.to_nsec() // divisor.to_nsec()
        if isinstance(divisor, int | float) and not isinstance(divisor, bool):
            return Duration.from_nsec(int(self.to_nsec() // divisor))
        return NotImplemented


class Time(TimeMsg):
    """rospy's Time: ``Time(secs, nsecs)``, ``Time.now()``, ``Time.from_sec(x)``, ``to_sec()``."""

    @classmethod
    def now(cls) -> Time:
        """The current ROS time (sim time with ``/use_sim_time``)."""
        return cls.from_nsec(now_ns())  # type: ignore[no-any-return]

    def __add__(self, other: object) -> Any:
        if isinstance(other, DurationMsg):
            return Time.from_nsec(self.to_nsec() + other.to_nsec())
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if isinstance(other, TimeMsg):
            return Duration.from_nsec(self.to_nsec() - other.to_nsec())
        if isinstance(other, DurationMsg):
            return Time.from_nsec(self.to_nsec() - other.to_nsec())
        return NotImplemented

    def __rsub__(self, other: object) -> Any:
        if isinstance(other, TimeMsg):
            return Duration.from_nsec(other.to_nsec() - self.to_nsec())
        return NotImplemented


def now_ns() -> int:
    """ROS time now, in integer nanoseconds."""
    node = process.node
    if node is None:
        return _time.time_ns()
    return node.get_clock().now().nanoseconds


def is_wallclock() -> bool:
    """Whether ROS time is the wall clock (no ``/use_sim_time``)."""
    node = process.node
    return node is None or not node.get_clock().use_sim_time


def get_rostime() -> Time:
    """The current ROS time as a ``rospy.Time``."""
    return Time.now()


def get_time() -> float:
    """The current ROS time in float seconds."""
    return now_ns() / 1e9
