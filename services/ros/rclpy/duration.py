"""``rclpy.duration.Duration``: a span of time in integer nanoseconds.

    Duration(seconds=2) > Duration(nanoseconds=5)      # True
    clock.now() - start > Duration(seconds=2)          # Time - Time is a Duration
"""

from __future__ import annotations

from typing import Any

from services.ros.pacing import S_TO_NS
from shared_models.builtin_interfaces import Duration as DurationMsg

__all__ = ["Duration", "NanosecondsOrder", "S_TO_NS"]


class NanosecondsOrder:
    """Comparisons by ``_nanoseconds`` with what ``_other`` accepts (it raises TypeError for
    the rest, as rclpy's Time and Duration do, ``==`` included)."""

    __slots__ = ()
    _nanoseconds: int

    def _other(self, other: object) -> int:
        raise NotImplementedError

    def __eq__(self, other: object) -> bool:
        return self._nanoseconds == self._other(other)

    def __ne__(self, other: object) -> bool:
        return self._nanoseconds != self._other(other)

    def __lt__(self, other: object) -> bool:
        return self._nanoseconds < self._other(other)

    def __le__(self, other: object) -> bool:
        return self._nanoseconds <= self._other(other)

    def __gt__(self, other: object) -> bool:
        return self._nanoseconds > self._other(other)

    def __ge__(self, other: object) -> bool:
        return self._nanoseconds >= self._other(other)


class Duration(NanosecondsOrder):
    """A span of time (negative allowed); compares only with another Duration, as rclpy's."""

    __slots__ = ("_nanoseconds",)

    def __init__(self, *, seconds: float = 0, nanoseconds: int = 0) -> None:
        total = int(seconds * S_TO_NS) + int(nanoseconds)
        if not -(2**63) <= total < 2**63:
            raise OverflowError(f"a Duration holds a signed 64-bit count of nanoseconds; got {total}")
        self._nanoseconds = total

    @property
    def nanoseconds(self) -> int:
        return self._nanoseconds

    @classmethod
    def from_msg(cls, msg: DurationMsg) -> Duration:
        """From a ``builtin_interfaces/msg/Duration``."""
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec)

    def to_msg(self) -> DurationMsg:
        """As a ``builtin_interfaces/msg/Duration``."""
        return DurationMsg.from_nsec(self._nanoseconds)  # type: ignore[no-any-return]

    def __repr__(self) -> str:
        return f"Duration(nanoseconds={self._nanoseconds})"

    def __str__(self) -> str:
        return f"{self._nanoseconds / S_TO_NS} seconds"

    def _other(self, other: object) -> int:
        if not isinstance(other, Duration):
            raise TypeError(f"Can't compare duration with object of type: {type(other)}")
        return other._nanoseconds


    def __hash__(self) -> int:
        return hash(self._nanoseconds)

    # Arithmetic as newer rclpy (Iron on) has it; Time +- Duration lives on Time.
    def __add__(self, other: Any) -> Any:
        if isinstance(other, Duration):
            return Duration(nanoseconds=self._nanoseconds + other._nanoseconds)
        return NotImplemented

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, Duration):
            return Duration(nanoseconds=self._nanoseconds - other._nanoseconds)
        return NotImplemented

    def __mul__(self, factor: Any) -> Any:
        if isinstance(factor, int | float) and not isinstance(factor, bool):
            return Duration(nanoseconds=int(self._nanoseconds * factor))
        return NotImplemented

    __rmul__ = __mul__

    def __neg__(self) -> Duration:
        return Duration(nanoseconds=-self._nanoseconds)
