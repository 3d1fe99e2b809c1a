"""Runtime behaviour the benchmark found wrong, pinned without timings.

(These belong with the runtime's tests; they live here because the benchmark found them.)
"""

from __future__ import annotations

import asyncio
import logging
import socket

from websockets.asyncio.server import ServerConnection, serve

from services.runtime.links import PublisherLink
from services.runtime.subscription import Subscription
from shared_models.std_msgs import Int32


async def test_a_burst_from_the_socket_does_not_overflow_a_subscription_that_keeps_up() -> None:
    # 1,000 frames written at once arrive in a few socket reads; a queue of 10 behind a callback
    # that takes no time must still see every one of them (drops are for slow callbacks).
    burst = 1000

    async def publisher(websocket: ServerConnection) -> None:
        for i in range(burst):
            await websocket.send(Int32(data=i).model_dump_json())
        await websocket.wait_closed()

    received: list[int] = []
    subscription = Subscription("/burst", Int32, lambda msg: received.append(msg.data), 10)
    async with serve(publisher, "127.0.0.1", 0, compression=None) as server:
        port = next(s for s in server.sockets if s.family == socket.AF_INET).getsockname()[1]
        link = PublisherLink(
            f"http://127.0.0.1:{port}",
            "/burst",
            lambda frame: subscription.enqueue(Int32.model_validate_json(frame)),
            queue_size=10,
            max_message_bytes=1 << 20,
            ping_interval_s=5.0,
            ping_timeout_s=5.0,
        )
        tasks = [asyncio.create_task(link.run()), asyncio.create_task(subscription.run(logging.getLogger("test")))]
        try:
            async with asyncio.timeout(20):
                while len(received) + subscription.dropped < burst:
                    await asyncio.sleep(0.01)
        finally:
            for task in tasks:
                task.cancel()
            await asyncio.gather(*tasks, return_exceptions=True)
    assert subscription.dropped == 0
    assert received == list(range(burst))
