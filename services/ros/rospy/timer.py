"""``rospy.Rate``, ``rospy.sleep`` and ``rospy.Timer``: waits on ROS time (sim time too).

    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        ...
        rate.sleep()

    rospy.Timer(rospy.Duration(0.5), lambda event: rospy.loginfo("tick at %s", event.current_real))

A sleep blocks the calling thread (the bridge's loop keeps the clock moving) and ends with
ROSInterruptException when the node shuts down. A Timer calls its callback on a thread of its
own, as rospy's does. The schedule and the waits are the façades' shared ones
(:mod:`services.ros.pacing`): a loop that falls far behind starts over from now instead of
bursting, and one whose clock went back (a simulator reset) starts over too.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from services.ros.pacing import S_TO_NS, LoopSchedule, sleep_until
from services.ros.rospy.core import process, report
from services.ros.rospy.exceptions import ROSInterruptException
from services.ros.rospy.rostime import Duration, Time, is_wallclock, now_ns
from shared_models.builtin_interfaces import Duration as DurationMsg

__all__ = ["Rate", "Timer", "TimerEvent", "sleep"]


def _running() -> bool:
    return not process.is_shutdown()


def _sim_time() -> bool:
    return not is_wallclock()


def _seconds(duration: float | DurationMsg, what: str) -> float:
    if isinstance(duration, DurationMsg):
        return duration.to_sec()
    if isinstance(duration, int | float) and not isinstance(duration, bool):
        return float(duration)
    raise TypeError(f"{what} takes seconds or a rospy.Duration, got {duration!r}")


def sleep(duration: float | DurationMsg) -> None:
    """Sleep for ``duration`` (seconds or a Duration) of ROS time; ROSInterruptException if the
    node shuts down first."""
    seconds = _seconds(duration, "rospy.sleep")
    if seconds <= 0:
        return
    if not sleep_until(now_ns, now_ns() + int(seconds * S_TO_NS), sim_time=_sim_time, ok=_running):
        raise ROSInterruptException("ROS shutdown request")


class Rate:
    """Keeps a loop at ``hz`` passes a second of ROS time."""

    def __init__(self, hz: float, reset: bool = False) -> None:
        if not (isinstance(hz, int | float) and hz > 0):
            raise ValueError(f"rospy.Rate needs a positive rate in Hz, got {hz!r}")
        self._schedule = LoopSchedule(int(S_TO_NS / hz), now_ns)

    def sleep(self) -> None:
        """Block until the next pass is due; ROSInterruptException if the node shuts down."""
        if not self._schedule.sleep(sim_time=_sim_time, ok=_running):
            raise ROSInterruptException("ROS shutdown request")

    def remaining(self) -> Duration:
        """Time left until the next pass is due."""
        return Duration.from_nsec(max(self._schedule.remaining_ns(), 0))  # type: ignore[no-any-return]


class TimerEvent:
    """What a Timer's callback gets: when this call and the last were due and happened."""

    def __init__(
        self, last_expected: Time | None, last_real: Time | None, current_expected: Time, current_real: Time,
        last_duration: float | None,
    ) -> None:  # fmt: skip
        self.last_expected = last_expected
        self.last_real = last_real
        self.current_expected = current_expected
        self.current_real = current_real
        self.last_duration = last_duration


class Timer(threading.Thread):
    """Calls ``callback(event)`` every ``period`` (a Duration) of ROS time, on its own thread;
    once only with ``oneshot=True``. ``shutdown()`` stops it."""

    def __init__(
        self, period: DurationMsg | float, callback: Callable[[TimerEvent], Any], oneshot: bool = False,
        reset: bool = False,
    ) -> None:  # fmt: skip
        super().__init__(name=f"rospy.Timer {getattr(callback, '__qualname__', callback)}", daemon=True)
        seconds = _seconds(period, "rospy.Timer")
        if seconds <= 0:
            raise ValueError(f"rospy.Timer needs a positive period, got {seconds} s")
        if not callable(callback):
            raise TypeError(f"rospy.Timer needs a callback function, got {callback!r}")
        self._period_ns = int(seconds * S_TO_NS)
        self._callback = callback
        self._oneshot = oneshot
        self._stopped = threading.Event()
        self.start()

    def shutdown(self) -> None:
        """Stop calling the callback."""
        self._stopped.set()

    def run(self) -> None:
        schedule = LoopSchedule(self._period_ns, now_ns)
        last_expected: Time | None = None
        last_real: Time | None = None
        last_duration: float | None = None

        def going() -> bool:
            return _running() and not self._stopped.is_set()

        while going():
            expected = Time.from_nsec(schedule.next_ns)
            if not schedule.sleep(sim_time=_sim_time, ok=going):
                return
            real = Time.now()
            started = now_ns()
            try:
                self._callback(TimerEvent(last_expected, last_real, expected, real, last_duration))
            except Exception as error:  # rospy's timer thread logs it and keeps going
                report(error, f"the timer callback {self.name.removeprefix('rospy.Timer ')}")
            last_expected, last_real, last_duration = expected, real, (now_ns() - started) / S_TO_NS
            if self._oneshot:
                return
