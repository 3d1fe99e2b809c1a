"""builtin_interfaces: Time and Duration."""

from __future__ import annotations

from shared_models._message import Int32, Message, UInt32

__all__ = ["Duration", "Time"]


class Time(Message):
    """A point in time: seconds and nanoseconds since the epoch (or since sim start)."""

    __ros_type__ = "builtin_interfaces/msg/Time"
    __ros_comment__ = (
        "# This message communicates ROS Time defined here:\n"
        "# https://design.ros2.org/articles/clock_and_time.html"
    )

    sec: Int32 = 0
    nanosec: UInt32 = 0

    @classmethod
    def from_seconds(cls, seconds: float) -> Time:
        """The Time for a float number of seconds."""
        nanoseconds = round(seconds * 1e9)
        return cls(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)

    def to_seconds(self) -> float:
        """This time as a float number of seconds."""
        return self.sec + self.nanosec * 1e-9


class Duration(Message):
    """A span of time: seconds and nanoseconds."""

    __ros_type__ = "builtin_interfaces/msg/Duration"
    __ros_comment__ = "# Duration defines a period between two time points."

    sec: Int32 = 0
    nanosec: UInt32 = 0
