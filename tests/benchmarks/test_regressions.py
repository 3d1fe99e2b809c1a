"""Runtime behaviour the benchmark found wrong, pinned without timings.

(These belong with the runtime's tests; they live here because the benchmark found them.)
"""

from __future__ import annotations

import asyncio
import logging
import socket
import time

from websockets.asyncio.server import ServerConnection, serve

from services.runtime.edge.encoding import Encoding
from services.runtime.edge.links import PublisherLink
from services.runtime.subscription import Subscription
from shared_models.std_msgs import Int32


def _deliver(subscription: Subscription, frame: str | bytes) -> int:
    """As a node wires its links: one message per frame here (this publisher sends no batches),
    and the count of messages the frame held."""
    subscription.receive(Int32.model_validate_json(frame))
    return 1


async def _burst_into(subscription: Subscription, burst: int, received: list[int]) -> None:
    """Send ``burst`` frames (data 0..burst-1) in one go over a real socket into ``subscription``
    and wait until each was delivered (into ``received``) or dropped."""

    async def publisher(websocket: ServerConnection) -> None:
        for i in range(burst):
            await websocket.send(Int32(data=i).model_dump_json())
        await websocket.wait_closed()

    async with serve(publisher, "127.0.0.1", 0, compression=None) as server:
        port = next(s for s in server.sockets if s.family == socket.AF_INET).getsockname()[1]
        link = PublisherLink(
            f"http://127.0.0.1:{port}",
            "/burst",
            lambda frame: _deliver(subscription, frame),
            queue_size=subscription.queue_size,
            encoding=Encoding.JSON,
            max_message_bytes=1 << 20,
            ping_interval_s=5.0,
            ping_timeout_s=5.0,
        )
        tasks = [asyncio.create_task(link.run()), asyncio.create_task(subscription.run(logging.getLogger("test")))]
        try:
            async with asyncio.timeout(20):
                while subscription.dropped + len(received) < burst:
                    await asyncio.sleep(0.01)
        finally:
            for task in tasks:
                task.cancel()
            await asyncio.gather(*tasks, return_exceptions=True)


async def test_a_burst_does_not_overflow_the_queue_of_a_quick_callback() -> None:
    # 1,000 frames written at once arrive in a few socket reads; a queue of 10 behind a callback
    # that takes no time must still see every one of them (drops are for slow callbacks).
    received: list[int] = []
    subscription = Subscription("/burst", Int32, lambda msg: received.append(msg.data), 10)
    await _burst_into(subscription, 1000, received)
    assert subscription.dropped == 0
    assert received == list(range(1000))


async def test_a_slow_callback_keeps_ros_drop_oldest_and_ends_on_the_newest() -> None:
    received: list[int] = []

    def slow(msg: Int32) -> None:
        time.sleep(0.002)  # slower than the stream: it must not work through stale messages
        received.append(msg.data)

    subscription = Subscription("/burst", Int32, slow, 1)
    await _burst_into(subscription, 300, received)
    assert subscription.dropped > 0
    assert received[-1] == 299
    assert received == sorted(received)


async def test_a_coroutine_callback_is_awaited_in_order() -> None:
    received: list[int] = []

    async def callback(msg: Int32) -> None:
        await asyncio.sleep(0)
        received.append(msg.data)

    subscription = Subscription("/burst", Int32, callback, 100)
    task = asyncio.create_task(subscription.run(logging.getLogger("test")))
    for i in range(50):
        subscription.enqueue(Int32(data=i))
    async with asyncio.timeout(5):
        while len(received) < 50:
            await asyncio.sleep(0.001)
    task.cancel()
    assert received == list(range(50))
