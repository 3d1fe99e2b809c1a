"""The per-connection outbox: bounded, oldest dropped, never blocking the publisher."""

from __future__ import annotations

import asyncio

from services.runtime.edge.outbox import Outbox


async def test_drain_returns_frames_in_order() -> None:
    outbox = Outbox(10)
    for i in range(3):
        outbox.push(str(i))
    assert await outbox.drain() == ["0", "1", "2"]


async def test_full_outbox_drops_oldest_and_counts() -> None:
    outbox = Outbox(3)
    for i in range(5):
        outbox.push(str(i))
    assert await outbox.drain() == ["2", "3", "4"]
    assert outbox.dropped == 2


async def test_latest_takes_only_newest() -> None:
    outbox = Outbox(1)
    outbox.push("old")
    outbox.push("new")
    assert await outbox.latest() == "new"


async def test_drain_waits_for_a_push() -> None:
    outbox = Outbox(4)
    waiter = asyncio.create_task(outbox.drain())
    await asyncio.sleep(0)
    assert not waiter.done()
    outbox.push("x")
    assert await asyncio.wait_for(waiter, 1.0) == ["x"]
