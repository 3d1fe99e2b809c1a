"""``rclpy.timer``: ``Timer`` (``node.create_timer(0.1, self.run_loop)``) and ``Rate``
(``node.create_rate(10).sleep()``).

The SDK's timer keeps the period on the bridge's loop (on sim time with ``use_sim_time``); each
tick marks the timer ready, and the executor runs the callback. A timer that is still ready when
it ticks again is not queued twice (ticks are skipped, as ROS's timers skip them).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from services.ros.bridge import bridge
from services.ros.errors import RosFacadeError
from services.ros.pacing import LoopSchedule
from services.ros.rclpy.callback_groups import CallbackGroup
from services.ros.rclpy.clock import Clock
from services.ros.rclpy.duration import S_TO_NS
from services.ros.rclpy.waitable import Job, Owner, Waitable, run_callback
from services.runtime.timer import Timer as RuntimeTimer

__all__ = ["ROSInterruptException", "Rate", "Timer"]


class ROSInterruptException(RosFacadeError):
    """A Rate's sleep ended because rclpy shut down."""


class Timer(Waitable):
    """Calls ``callback()`` every ``timer_period_sec`` (made by ``Node.create_timer``)."""

    def __init__(
        self, node: Owner, callback: Callable[[], Any] | None, period_s: float, clock: Clock,
        callback_group: CallbackGroup | None,
    ) -> None:  # fmt: skip
        super().__init__(node, callback_group)
        self.callback = callback
        self._clock = clock
        self._period_ns = int(period_s * S_TO_NS)
        self._due = False
        self._last_call_ns = clock.now().nanoseconds
        self._timer: RuntimeTimer | None = None
        name = getattr(callback, "__qualname__", repr(callback))
        self.what = f"the timer callback {name}"

    @property
    def timer_period_ns(self) -> int:
        return self._period_ns

    @property
    def clock(self) -> Clock:
        return self._clock

    def _tick(self) -> None:
        """The SDK's timer fired (on the bridge's loop)."""
        if not self._due:
            self._due = True
            self._notify()

    def _has_work(self) -> bool:
        return self._due

    def _take(self) -> Job | None:
        if not self._due:
            return None
        self._due = False
        self._last_call_ns = self._clock.now().nanoseconds
        callback = self.callback
        if callback is None:
            return None
        return lambda: run_callback(callback)

    def is_ready(self) -> bool:
        return self._due

    def is_canceled(self) -> bool:
        return self._timer is not None and self._timer.is_canceled()

    def cancel(self) -> None:
        """Stop calling the callback (``reset()`` starts it again)."""
        self._due = False
        if self._timer is not None:
            bridge.call(self._timer.cancel)

    def reset(self) -> None:
        """Start the period over from now (and un-cancel)."""
        if self._timer is not None:
            bridge.call(self._timer.reset)

    def time_since_last_call(self) -> int:
        """Nanoseconds since the callback was last run."""
        return self._clock.now().nanoseconds - self._last_call_ns

    def time_until_next_call(self) -> int:
        return max(self._period_ns - self.time_since_last_call(), 0)

    def destroy(self) -> None:
        self.cancel()


class Rate:
    """Sleeps so that a loop runs at ``frequency`` Hz on the node's clock (sim time too).

    Works from the main thread while another thread spins, and also when nothing spins (the
    clock is the bridge's, not the executor's). The schedule is :class:`~services.ros.pacing.LoopSchedule`.
    """

    def __init__(self, frequency: float, clock: Clock) -> None:
        if not frequency > 0:
            raise ValueError(f"a Rate's frequency must be positive Hz, got {frequency!r}")
        self._clock = clock
        self._schedule = LoopSchedule(int(S_TO_NS / frequency), lambda: clock.now().nanoseconds)
        self._destroyed = False

    def sleep(self) -> None:
        """Block until the next period starts; ROSInterruptException if rclpy shuts down."""
        from services.ros.rclpy.context import default_context

        if self._destroyed:
            raise ROSInterruptException("this Rate was destroyed")
        if not self._schedule.sleep(sim_time=lambda: self._clock.ros_time_is_active, ok=default_context.ok):
            raise ROSInterruptException("rclpy was shut down during a Rate's sleep")

    def destroy(self) -> None:
        self._destroyed = True
