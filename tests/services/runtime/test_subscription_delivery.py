"""How a subscription hands messages to its callback: inline from a socket when that is safe,
through its delivery task otherwise (unit level: no sockets, the Subscription alone)."""

from __future__ import annotations

import asyncio
import logging
import time

import pytest

from services.runtime.subscription import Subscription
from shared_models.std_msgs import String

pytestmark = pytest.mark.timeout(10)


def _msg(i: int) -> String:
    return String(data=str(i))


async def test_socket_message_goes_to_a_quick_plain_callback_at_once() -> None:
    got: list[str] = []
    subscription = Subscription("/t", String, lambda msg: got.append(msg.data), 10)
    subscription.receive(_msg(1))
    assert got == ["1"]  # no delivery task running: called from receive itself


async def test_local_publish_never_runs_the_callback_inside_publish() -> None:
    got: list[str] = []
    subscription = Subscription("/t", String, lambda msg: got.append(msg.data), 10)
    subscription.enqueue(_msg(1))
    assert got == []
    task = asyncio.create_task(subscription.run(logging.getLogger("test")))
    try:
        async with asyncio.timeout(5):
            while not got:
                await asyncio.sleep(0)
    finally:
        task.cancel()
    assert got == ["1"]


async def test_socket_message_waits_behind_queued_ones_to_keep_the_order() -> None:
    got: list[str] = []
    subscription = Subscription("/t", String, lambda msg: got.append(msg.data), 10)
    subscription.enqueue(_msg(1))
    subscription.receive(_msg(2))
    assert got == []
    task = asyncio.create_task(subscription.run(logging.getLogger("test")))
    try:
        async with asyncio.timeout(5):
            while len(got) < 2:
                await asyncio.sleep(0)
    finally:
        task.cancel()
    assert got == ["1", "2"]


async def test_slow_callback_is_called_inline_at_most_once_then_queued() -> None:
    got: list[str] = []

    def slow(msg: String) -> None:
        time.sleep(0.005)
        got.append(msg.data)

    subscription = Subscription("/t", String, slow, 10)
    subscription.receive(_msg(1))  # unknown speed: called, and measured
    subscription.receive(_msg(2))  # known slow: left to the delivery task
    assert got == ["1"]


async def test_coroutine_callback_is_never_called_inline() -> None:
    got: list[str] = []

    async def callback(msg: String) -> None:
        got.append(msg.data)

    subscription = Subscription("/t", String, callback, 10)
    subscription.receive(_msg(1))
    assert got == []


async def test_local_publish_into_a_full_queue_drops_the_oldest_and_calls_nothing() -> None:
    got: list[str] = []
    subscription = Subscription("/t", String, lambda msg: got.append(msg.data), 5)
    for i in range(20):
        subscription.enqueue(_msg(i))
    assert got == [] and subscription.dropped == 15
