"""builtin_interfaces: Time and Duration, which compare, convert and add up as ROS's times do.

The JSON stays ROS 2's ``{"sec": .., "nanosec": ..}``; in Python the ROS 1 spellings work too:
``Time(5, 500)``, ``Duration(0.5)``, ``stamp.secs``, ``stamp.to_sec()``, ``end - start``.
"""

from __future__ import annotations

import math
from typing import Any

from shared_models._message import Int32, Message, UInt32

__all__ = ["Duration", "Time", "split_seconds"]

_NS_PER_S = 1_000_000_000
# ROS 1's keyword names of the two fields.
_ROS1_NAMES = {"secs": "sec", "nsecs": "nanosec"}


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


class _SecondsAndNanoseconds(Message):
    """What Time and Duration share: the two fields, ROS 1's constructor forms and conversions."""

    sec: Int32 = 0
    nanosec: UInt32 = 0

    def __init__(self, /, *args: Any, **data: Any) -> None:
        """``Time(sec=1, nanosec=5)`` as ROS 2; ``Time(1, 5)``, ``Time(1.5)`` or ``Time(secs=1,
        nsecs=5)`` as ROS 1 (genpy), where float seconds are split and nanoseconds carried."""
        if args or "secs" in data or "nsecs" in data:
            data = self._from_ros1(args, data)
        self.__pydantic_validator__.validate_python(data, self_instance=self)

    __init__.__pydantic_base_init__ = True  # type: ignore[attr-defined]  # see Message.__init__

    @classmethod
    def _from_ros1(cls, args: tuple[Any, ...], data: dict[str, Any]) -> dict[str, Any]:
        if args:
            data = cls._positional(args, data)
        else:
            data = dict(data)
            for ros1, ros2 in _ROS1_NAMES.items():
                if ros1 in data:
                    if ros2 in data:
                        raise TypeError(f"{cls.__name__}() got both {ros1} and {ros2}")
                    data[ros2] = data.pop(ros1)
        sec, nanosec = data.get("sec", 0), data.get("nanosec", 0)
        if not (_is_number(sec) and _is_number(nanosec)):
            return data  # the validator names what is wrong
        if isinstance(sec, float):
            nanoseconds = round(sec * _NS_PER_S) + round(nanosec)
        else:
            nanoseconds = sec * _NS_PER_S + round(nanosec)
        data["sec"], data["nanosec"] = divmod(nanoseconds, _NS_PER_S)
        return data

    # Conversions: ROS 1's names and the longer ROS 2 spelling of float seconds.
    @classmethod
    def from_nsec(cls, nanoseconds: int) -> Any:
        """The value for an integer number of nanoseconds."""
        sec, nanosec = divmod(int(nanoseconds), _NS_PER_S)
        return cls(sec=sec, nanosec=nanosec)

    @classmethod
    def from_sec(cls, seconds: float) -> Any:
        """The value for a float number of seconds (``rospy.Time.from_sec``)."""
        sec, nanosec = split_seconds(seconds)
        return cls(sec=sec, nanosec=nanosec)

    from_seconds = from_sec

    def to_nsec(self) -> int:
        """This value as an integer number of nanoseconds."""
        return self.sec * _NS_PER_S + self.nanosec

    def to_sec(self) -> float:
        """This value as a float number of seconds."""
        return self.sec + self.nanosec * 1e-9

    to_seconds = to_sec

    def is_zero(self) -> bool:
        """Whether both fields are zero."""
        return self.sec == 0 and self.nanosec == 0

    # ROS 1's field names, read and written as the ROS 2 fields.
    @property
    def secs(self) -> int:
        """ROS 1's name of ``sec``."""
        return self.sec

    @secs.setter
    def secs(self, value: int) -> None:
        self.sec = value

    @property
    def nsecs(self) -> int:
        """ROS 1's name of ``nanosec``."""
        return self.nanosec

    @nsecs.setter
    def nsecs(self, value: int) -> None:
        self.nanosec = value

    # Ordering and equality within one kind only: a Time is not comparable with a Duration (as
    # in ROS), but a Time of a façade's subclass (rospy.Time) is one with a received stamp.
    def _same_kind(self, other: object) -> bool:
        return isinstance(other, _SecondsAndNanoseconds) and isinstance(other, Time) == isinstance(self, Time)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, _SecondsAndNanoseconds):
            return NotImplemented
        return self._same_kind(other) and self.to_nsec() == other.to_nsec()

    def __lt__(self, other: object) -> bool:
        if not self._same_kind(other):
            return NotImplemented
        return self.to_nsec() < other.to_nsec()  # type: ignore[attr-defined]

    def __le__(self, other: object) -> bool:
        if not self._same_kind(other):
            return NotImplemented
        return self.to_nsec() <= other.to_nsec()  # type: ignore[attr-defined]

    def __gt__(self, other: object) -> bool:
        if not self._same_kind(other):
            return NotImplemented
        return self.to_nsec() > other.to_nsec()  # type: ignore[attr-defined]

    def __ge__(self, other: object) -> bool:
        if not self._same_kind(other):
            return NotImplemented
        return self.to_nsec() >= other.to_nsec()  # type: ignore[attr-defined]

    # Hashable as rospy's times are (a stamp as a dict key); mutating a key is the caller's risk.
    def __hash__(self) -> int:
        return hash((isinstance(self, Time), self.sec, self.nanosec))


class Time(_SecondsAndNanoseconds):
    """A point in time: seconds and nanoseconds since the epoch (or since sim start).

    ``Time - Time`` is a :class:`Duration`; ``Time + Duration`` and ``Time - Duration`` a Time.
    """

    __ros_type__ = "builtin_interfaces/msg/Time"
    __ros_comment__ = (
        "# This message communicates ROS Time defined here:\n"
        "# https://design.ros2.org/articles/clock_and_time.html"
    )

    def __add__(self, other: object) -> Time:
        if not isinstance(other, Duration):
            return NotImplemented
        return Time.from_nsec(self.to_nsec() + other.to_nsec())

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if isinstance(other, Time):
            return Duration.from_nsec(self.to_nsec() - other.to_nsec())
        if isinstance(other, Duration):
            return Time.from_nsec(self.to_nsec() - other.to_nsec())
        return NotImplemented


class Duration(_SecondsAndNanoseconds):
    """A span of time: seconds and nanoseconds (negative spans have a negative ``sec``).

    Durations add, subtract, negate, scale by a number and divide (by a number, or by another
    Duration for their ratio), as rospy's do.
    """

    __ros_type__ = "builtin_interfaces/msg/Duration"
    __ros_comment__ = "# Duration defines a period between two time points."

    def __add__(self, other: object) -> Any:
        if isinstance(other, Duration):
            return Duration.from_nsec(self.to_nsec() + other.to_nsec())
        return NotImplemented  # Duration + Time is Time.__radd__

    def __sub__(self, other: object) -> Duration:
        if not isinstance(other, Duration):
            return NotImplemented
        return Duration.from_nsec(self.to_nsec() - other.to_nsec())

    def __neg__(self) -> Duration:
        return Duration.from_nsec(-self.to_nsec())

    def __abs__(self) -> Duration:
        return Duration.from_nsec(abs(self.to_nsec()))

    def __mul__(self, factor: object) -> Duration:
        if not _is_number(factor):
            return NotImplemented
        return Duration.from_nsec(round(self.to_nsec() * factor))  # type: ignore[operator]

    __rmul__ = __mul__

    def __truediv__(self, divisor: object) -> Any:
        if isinstance(divisor, Duration):
            return self.to_nsec() / divisor.to_nsec()
        if not _is_number(divisor):
            return NotImplemented
        return Duration.from_nsec(round(self.to_nsec() / divisor))  # type: ignore[operator]


def split_seconds(seconds: float) -> tuple[int, int]:
    """``(sec, nanosec)`` of a float number of seconds, rounded to the nanosecond as
    ``Time.from_sec`` does: for a hot loop that stamps plain dicts rather than Time objects."""
    return divmod(round(seconds * _NS_PER_S), _NS_PER_S)
