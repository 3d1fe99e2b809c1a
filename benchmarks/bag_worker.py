"""Workers of the recording benchmarks.

    python -m benchmarks.bag_worker listen /bench/a /bench/b   # READY, then RESULT on `stop`
    python -m benchmarks.bag_worker publish /bench/small 3.0   # READY, RESULT when done

``listen`` keeps the arrival time of every message of its topics, read raw (``raw=True``): the
arrival is taken before anything else happens to the frame, whose ``header.seq`` says which
recorded message it is. ``publish`` waits for one subscriber, then publishes small stamped
frames, each with its own ``seq``, as fast as it can for the given seconds, already serialised
(``publish(frame)``): the recorder, not the publisher's serialisation, is what is measured.
"""

from __future__ import annotations

import asyncio
import json
import sys
import time

from benchmarks.sink import emit, wait_for_stop_async
from services.runtime import Node, NodeSettings
from shared_models.geometry_msgs import PointStamped


async def listen(topics: list[str]) -> None:
    node = Node("bench_bag_listener", settings=NodeSettings(port=0))
    arrivals: list[tuple[str, str, float]] = []
    for topic in topics:
        node.create_subscription(
            PointStamped, topic, lambda frame, t=topic: arrivals.append((t, frame, time.monotonic())), 10_000, raw=True
        )
    await node.start()
    try:
        emit("READY", {"url": node.url})
        await wait_for_stop_async()
        emit("RESULT", {"arrivals": [[t, json.loads(f)["header"]["seq"], at] for t, f, at in arrivals]})
    finally:
        await node.stop()


_TEMPLATE = '{"header":{"seq":%d,"stamp":{"sec":1,"nanosec":2},"frame_id":"map"},"point":{"x":1.0,"y":2.0,"z":3.0}}'
_BURST = 10


async def publish(topic: str, seconds: float) -> None:
    node = Node("bench_bag_publisher", settings=NodeSettings(port=0))
    publisher = node.create_publisher(PointStamped, topic, 10_000)
    await node.start()
    try:
        async with asyncio.timeout(30):
            while publisher.get_subscription_count() < 1:
                await asyncio.sleep(0.01)
        emit("READY", {"url": node.url})
        sent, start = 0, time.monotonic()
        end = start + seconds
        send = publisher.publish
        while time.monotonic() < end:
            for _ in range(_BURST):
                sent += 1
                send(_TEMPLATE % sent)
            await asyncio.sleep(0)
        wall_s = time.monotonic() - start
        await asyncio.sleep(0.5)  # the outbox drains to the recorder
        emit("RESULT", {"sent": sent, "wall_s": wall_s, "rate": sent / wall_s})
    finally:
        await node.stop()


if __name__ == "__main__":
    role, *rest = sys.argv[1:]
    asyncio.run(listen(rest) if role == "listen" else publish(rest[0], float(rest[1])))
