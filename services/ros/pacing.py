"""Blocking waits on a ROS clock, shared by the façades: ``Rate.sleep()``, ``sleep()``, timers.

A program's thread blocks here while the bridge's loop moves the clock (the wall clock, or sim
time from ``/clock``). On sim time a wait polls briefly, since the simulator may run many times
faster than real time; on the wall clock it sleeps for what is left (at most a tenth of a
second at a time, so a shutdown is seen quickly). Each façade says what "still running" means
(``ok``) and raises its own exception when a wait is cut short.

    schedule = LoopSchedule(period_ns=100_000_000, now_ns=clock_now_ns)
    while running():
        if not schedule.sleep(clock_now_ns, sim_time=lambda: True, ok=running):
            break
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from services.runtime.clock import Clock as RuntimeClock
from services.runtime.lockstep.activity import ACTIVITY

__all__ = [
    "FIRST_CLOCK_WAIT_S",
    "S_TO_NS",
    "LoopSchedule",
    "sleep_until",
    "thread_waits_for_work",
    "wait_for_first_clock",
]

S_TO_NS = 1_000_000_000
FIRST_CLOCK_WAIT_S = 2.0
_WALL_STEP_S = 0.1  # longest single sleep on the wall clock: how soon a shutdown is seen
_SIM_POLL_S = 0.002  # how often a wait on sim time looks at the clock again

NowNs = Callable[[], int]
Flag = Callable[[], bool]


def _nap(left_ns: int, sim_time: bool) -> None:
    time.sleep(_SIM_POLL_S if sim_time else min(left_ns / S_TO_NS, _WALL_STEP_S))


class _Threads:
    """Which program threads a lockstep run (:mod:`services.runtime.lockstep`) must wait for:
    those waiting on sim time whose time has come (woken within a poll), and those a sim-time
    wait let go, until they wait again (on sim time, or for work: ``rospy.spin``, an rclpy
    executor). A thread that never waits on sim time is never waited for."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._waiting: dict[threading.Thread, tuple[NowNs, int]] = {}
        self._running: set[threading.Thread] = set()
        ACTIVITY.watch(self, self.busy)

    def wait(self, now_ns: NowNs, until_ns: int) -> None:
        with self._lock:
            thread = threading.current_thread()
            self._running.discard(thread)
            self._waiting[thread] = (now_ns, until_ns)

    def woke(self) -> None:
        with self._lock:
            thread = threading.current_thread()
            self._waiting.pop(thread, None)
            self._running.add(thread)

    def waits_for_work(self) -> None:
        with self._lock:
            self._running.discard(threading.current_thread())

    def busy(self) -> bool:
        with self._lock:
            if any(thread.is_alive() for thread in self._running):
                return True
            waiting = list(self._waiting.items())
        return any(thread.is_alive() and now_ns() >= until for thread, (now_ns, until) in waiting)


_THREADS = _Threads()


def thread_waits_for_work() -> None:
    """The calling thread now waits for messages or shutdown, not on sim time (``rospy.spin``,
    an rclpy executor's wait): a lockstep run need not wait for it."""
    _THREADS.waits_for_work()


def sleep_until(now_ns: NowNs, until_ns: int, *, sim_time: Flag, ok: Flag) -> bool:
    """Block until ``now_ns()`` reaches ``until_ns``; False if ``ok()`` turned False first."""
    on_sim_time = sim_time()
    if on_sim_time:
        _THREADS.wait(now_ns, until_ns)
    try:
        while ok():
            left_ns = until_ns - now_ns()
            if left_ns <= 0:
                return True
            _nap(left_ns, sim_time())
        return False
    finally:
        if on_sim_time:
            _THREADS.woke()


class LoopSchedule:
    """When each pass of a loop at a fixed period is due (``Rate``'s schedule).

    A sleep that finds itself behind by more than a period starts the schedule over from now
    instead of bursting; a clock that went back (a simulator reset) starts it over too, rather
    than sleeping until the old time comes round again.
    """

    def __init__(self, period_ns: int, now_ns: NowNs) -> None:
        if period_ns <= 0:
            raise ValueError(f"a loop's period must be positive, got {period_ns} ns")
        self.period_ns = period_ns
        self._now_ns = now_ns
        self.next_ns = now_ns() + period_ns

    def remaining_ns(self) -> int:
        """Time left until the next pass is due (negative when late)."""
        return self.next_ns - self._now_ns()

    def sleep(self, *, sim_time: Flag, ok: Flag) -> bool:
        """Block until the next pass is due; False if ``ok()`` turned False first."""
        now = self._now_ns()
        if now - self.next_ns > self.period_ns:  # far behind (or the clock jumped ahead)
            self.next_ns = now
        on_sim_time = sim_time()
        if on_sim_time:
            _THREADS.wait(lambda: -self.remaining_ns(), 0)  # due when nothing remains
        try:
            while True:
                if not ok():
                    return False
                now = self._now_ns()
                left_ns = self.next_ns - now
                if left_ns <= 0:
                    break
                if left_ns > self.period_ns:  # the clock went back: from now on
                    self.next_ns = now + self.period_ns
                _nap(left_ns, sim_time())
        finally:
            if on_sim_time:
                _THREADS.woke()
        self.next_ns += self.period_ns
        return True


def wait_for_first_clock(clock: RuntimeClock, timeout_s: float = FIRST_CLOCK_WAIT_S) -> None:
    """On sim time, wait (a moment at most) for the first ``/clock``: ROS time reads zero until
    then, and a program that takes the time at start (a timed leg, a timeout) would otherwise
    measure from zero, a classic stumble with both rospy and rclpy."""
    if clock.driven:
        return  # a lockstep run moves the clock once every node is up: it starts at zero
    deadline = time.monotonic() + timeout_s
    while clock.use_sim_time and clock.now().nanoseconds == 0 and time.monotonic() < deadline:
        time.sleep(0.005)
