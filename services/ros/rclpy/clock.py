"""``rclpy.clock``: ``node.get_clock().now()``, and sleeping on a clock.

A node's clock is ROS time: the wall clock, or the simulator's ``/clock`` when the node's
``use_sim_time`` parameter is set (it reads the SDK node's clock, which follows ``/clock``).
"""

from __future__ import annotations

import time as _time

from services.ros.pacing import sleep_until
from services.ros.rclpy.clock_type import ClockType
from services.ros.rclpy.duration import Duration
from services.ros.rclpy.time import Time
from services.runtime.clock import Clock as RuntimeClock

__all__ = ["Clock", "ClockType", "ROSClock"]


class Clock:
    """A clock of ``clock_type``: ROS_TIME (a node's; sim time with ``use_sim_time``),
    SYSTEM_TIME or STEADY_TIME."""

    def __init__(self, *, clock_type: ClockType = ClockType.SYSTEM_TIME, _source: RuntimeClock | None = None) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        self._clock_type = clock_type
        self._source = _source

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    @property
    def ros_time_is_active(self) -> bool:
        """Whether this clock follows /clock (the node's ``use_sim_time``)."""
        return self._source is not None and self._source.use_sim_time

    def now(self) -> Time:
        """The current time on this clock."""
        if self._source is not None:
            nanoseconds = self._source.now().nanoseconds
        elif self._clock_type == ClockType.STEADY_TIME:
            nanoseconds = _time.monotonic_ns()
        else:
            nanoseconds = _time.time_ns()
        return Time(nanoseconds=nanoseconds, clock_type=self._clock_type)

    def sleep_until(self, until: Time) -> bool:
        """Block until this clock reaches ``until``; True when it did (False if rclpy shut down)."""
        from services.ros.rclpy.context import default_context

        if until.clock_type != self._clock_type:
            raise ValueError("until's clock type does not match this clock's type")
        return sleep_until(
            lambda: self.now().nanoseconds,
            until.nanoseconds,
            sim_time=lambda: self.ros_time_is_active,
            ok=default_context.ok,
        )

    def sleep_for(self, rel_time: Duration) -> bool:
        """Block for ``rel_time`` on this clock; True when it passed."""
        return self.sleep_until(self.now() + rel_time)


class ROSClock(Clock):
    """A ROS_TIME clock (what ``node.get_clock()`` returns)."""

    def __init__(self, _source: RuntimeClock | None = None) -> None:
        super().__init__(clock_type=ClockType.ROS_TIME, _source=_source)
