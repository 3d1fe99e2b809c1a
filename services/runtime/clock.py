"""Node clocks: wall time, or sim time driven by the ``/clock`` topic (``use_sim_time``)."""

from __future__ import annotations

import asyncio
import time

from shared_models.builtin_interfaces import Time

__all__ = ["Clock", "ClockTime"]


class ClockTime:
    """A point in time on a node's clock, as rclpy's ``Time``: ``now().to_msg()``."""

    __slots__ = ("nanoseconds",)

    def __init__(self, nanoseconds: int) -> None:
        self.nanoseconds = nanoseconds

    def to_msg(self) -> Time:
        """This time as a ``builtin_interfaces/msg/Time`` message."""
        sec, nanosec = divmod(self.nanoseconds, 1_000_000_000)
        return Time(sec=sec, nanosec=nanosec)

    def seconds(self) -> float:
        """This time as float seconds."""
        return self.nanoseconds * 1e-9

    def __repr__(self) -> str:
        return f"ClockTime(nanoseconds={self.nanoseconds})"


class Clock:
    """Wall clock, or sim clock following ``/clock`` messages when ``use_sim_time`` is set.

    Sim time starts at zero and only moves when a ``/clock`` message arrives; timers on a sim
    clock therefore run at the simulator's pace (faster or slower than real time). When sim time
    jumps back (a restarted simulator starts again at zero), waits end and timers start over from
    the new time, as ROS timers do on a backwards jump, instead of sleeping until the old time.
    """

    def __init__(self, *, use_sim_time: bool = False) -> None:
        self.use_sim_time = use_sim_time
        # Moved by a lockstep run's agent (services.runtime.lockstep), not by /clock messages.
        self.driven = False
        self._sim_ns = 0
        self._advanced = asyncio.Event()
        self.jumps_back = 0

    def now(self) -> ClockTime:
        """The current time on this clock."""
        if self.use_sim_time:
            return ClockTime(self._sim_ns)
        return ClockTime(time.time_ns())

    def now_s(self) -> float:
        """The current time in float seconds (monotonic when on wall time)."""
        if self.use_sim_time:
            return self._sim_ns * 1e-9
        return time.monotonic()

    def set_use_sim_time(self, enabled: bool) -> None:
        """Follow ``/clock`` (or the wall clock again); waits on the old time base end, and
        timers start their period over on the new one."""
        if enabled != self.use_sim_time:
            self.use_sim_time = enabled
            self.jumps_back += 1
            self._advanced.set()

    def set_sim_time(self, stamp: Time) -> None:
        """Advance sim time to ``stamp`` (called for each ``/clock`` message)."""
        sim_ns = stamp.sec * 1_000_000_000 + stamp.nanosec
        if sim_ns < self._sim_ns:
            self.jumps_back += 1
        self._sim_ns = sim_ns
        self._advanced.set()

    async def sleep_until(self, deadline_s: float) -> None:
        """Wait until ``now_s()`` reaches ``deadline_s``, or sim time jumps back."""
        if not self.use_sim_time:
            delay = deadline_s - time.monotonic()
            if delay > 0:
                await asyncio.sleep(delay)
            return
        jumps_back = self.jumps_back
        while self._sim_ns * 1e-9 < deadline_s and self.jumps_back == jumps_back:
            self._advanced.clear()
            await self._advanced.wait()
