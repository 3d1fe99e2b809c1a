"""Timers: cancel and reset (unit level: a Timer on a counting wall clock, no node)."""

from __future__ import annotations

import asyncio
import logging

import pytest

from services.runtime.clock import Clock
from services.runtime.timer import Timer

pytestmark = pytest.mark.timeout(10)


class CountingClock(Clock):
    """The wall clock, counting how often a timer goes to sleep on it."""

    def __init__(self) -> None:
        super().__init__()
        self.sleeps = 0

    async def sleep_until(self, deadline_s: float) -> None:
        self.sleeps += 1
        await super().sleep_until(deadline_s)


async def test_cancelled_timer_idles_until_reset_and_then_ticks_again() -> None:
    clock = CountingClock()
    ticks = asyncio.Event()
    timer = Timer(0.01, ticks.set, clock)
    task = asyncio.create_task(timer.run(logging.getLogger("test")))
    try:
        await asyncio.wait_for(ticks.wait(), 5)
        timer.cancel()
        ticks.clear()
        await asyncio.sleep(0.2)  # 20 periods: a cancelled timer must neither tick nor spin
        assert not ticks.is_set()
        assert clock.sleeps < 10, f"a cancelled timer went to sleep {clock.sleeps} times"
        timer.reset()
        await asyncio.wait_for(ticks.wait(), 5)
    finally:
        task.cancel()
