"""Timers: ``node.create_timer(0.1, self.run_loop)`` calls ``run_loop`` ten times a second."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any

from services.runtime.callbacks import call_user
from services.runtime.clock import Clock

__all__ = ["Timer"]


class Timer:
    """Calls a callback every ``period_s`` on a clock, without drift; missed ticks are skipped."""

    def __init__(self, period_s: float, callback: Callable[[], Any], clock: Clock) -> None:
        if not period_s > 0:
            raise ValueError(f"timer period must be positive seconds, got {period_s!r}")
        self.timer_period_s = period_s
        self.callback = callback
        self._clock = clock
        self._canceled = False
        self._reset = asyncio.Event()
        self._due_s: float | None = None  # when the next call is due, once running
        self._calling = False

    def cancel(self) -> None:
        """Stop calling the callback."""
        self._canceled = True
        self._reset.set()

    def is_canceled(self) -> bool:
        """Whether :meth:`cancel` was called."""
        return self._canceled

    def reset(self) -> None:
        """Restart the period from now (and un-cancel)."""
        self._canceled = False
        self._reset.set()

    @property
    def busy(self) -> bool:
        """On sim time: whether a call is due or running (what a lockstep run waits for). A
        wall-clock timer is never waited for: its calls belong to no step of the world."""
        if not self._clock.use_sim_time or self._canceled:
            return False
        due_s = self._due_s
        return self._calling or (due_s is not None and due_s <= self._clock.now_s())

    async def run(self, logger: logging.Logger) -> None:
        """Tick until cancelled (the task is owned by the node)."""
        clock = self._clock
        what = f"timer callback {getattr(self.callback, '__qualname__', self.callback)!r}"
        due_s = self._due_s = clock.now_s() + self.timer_period_s
        while True:
            self._due_s = due_s
            period_s = self.timer_period_s  # read every tick: a new period takes effect at once
            sleeper = asyncio.ensure_future(clock.sleep_until(due_s))
            resetter = asyncio.ensure_future(self._reset.wait())
            try:
                done, _ = await asyncio.wait({sleeper, resetter}, return_when=asyncio.FIRST_COMPLETED)
            finally:
                sleeper.cancel()
                resetter.cancel()
            if resetter in done:
                self._reset.clear()
                due_s = clock.now_s() + self.timer_period_s
                continue
            if self._canceled:
                await self._reset.wait()  # idle until reset(); the next pass re-arms the period
                continue
            if clock.use_sim_time and clock.now_s() < due_s:  # sim time jumped back (a restarted simulator)
                due_s = clock.now_s() + period_s
                continue
            self._calling = True
            try:
                await call_user(self.callback, logger=logger, what=what)
            finally:
                self._calling = False
            due_s += period_s
            now_s = clock.now_s()
            if due_s <= now_s:  # fell behind (slow callback or paused clock): skip, don't burst
                due_s = now_s + period_s
