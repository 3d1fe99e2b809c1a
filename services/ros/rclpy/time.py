"""``rclpy.time.Time``: a point in time on one clock, in integer nanoseconds.

    start = node.get_clock().now()
    ...
    if node.get_clock().now() - start > Duration(seconds=2): ...
    header.stamp = node.get_clock().now().to_msg()
"""

from __future__ import annotations

from typing import Any

from services.ros.rclpy.clock_type import ClockType
from services.ros.rclpy.duration import S_TO_NS, Duration, NanosecondsOrder
from shared_models.builtin_interfaces import Time as TimeMsg

__all__ = ["Time"]


class Time(NanosecondsOrder):
    """A time on a clock of ``clock_type``; times of different clock types do not mix (TypeError)."""

    __slots__ = ("_clock_type", "_nanoseconds")

    def __init__(
        self, *, seconds: float = 0, nanoseconds: int = 0, clock_type: ClockType = ClockType.SYSTEM_TIME
    ) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        if seconds < 0 or nanoseconds < 0:
            raise ValueError("Seconds and nanoseconds must not be negative")
        total = int(seconds * S_TO_NS) + int(nanoseconds)
        if total >= 2**63:
            raise OverflowError(f"Total nanoseconds value is too large to store in C time point: {total}")
        self._nanoseconds = total
        self._clock_type = clock_type

    @property
    def nanoseconds(self) -> int:
        return self._nanoseconds

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    def seconds_nanoseconds(self) -> tuple[int, int]:
        """(whole seconds, the nanoseconds after them)."""
        return divmod(self._nanoseconds, S_TO_NS)

    def to_msg(self) -> TimeMsg:
        """As a ``builtin_interfaces/msg/Time`` (a header's ``stamp``)."""
        return TimeMsg.from_nsec(self._nanoseconds)  # type: ignore[no-any-return]

    @classmethod
    def from_msg(cls, msg: TimeMsg, clock_type: ClockType = ClockType.ROS_TIME) -> Time:
        """From a ``builtin_interfaces/msg/Time`` (a received stamp)."""
        if not isinstance(msg, TimeMsg):
            raise TypeError("Must pass a builtin_interfaces.msg.Time object")
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec, clock_type=clock_type)

    def __repr__(self) -> str:
        return f"Time(nanoseconds={self._nanoseconds}, clock_type={self._clock_type.name})"

    def __add__(self, other: Any) -> Time:
        if isinstance(other, Duration):
            return Time(nanoseconds=self._nanoseconds + other.nanoseconds, clock_type=self._clock_type)
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, Time):
            if other._clock_type != self._clock_type:
                raise TypeError("Can't subtract times with different clock types")
            return Duration(nanoseconds=self._nanoseconds - other._nanoseconds)
        if isinstance(other, Duration):
            return Time(nanoseconds=self._nanoseconds - other.nanoseconds, clock_type=self._clock_type)
        return NotImplemented

    def _other(self, other: object) -> int:
        if not isinstance(other, Time):
            raise TypeError(f"Can't compare time with object of type: {type(other)}")
        if other._clock_type != self._clock_type:
            raise TypeError("Can't compare times with different clock types")
        return other._nanoseconds


    def __hash__(self) -> int:
        return hash((self._nanoseconds, self._clock_type))
