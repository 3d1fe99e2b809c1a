"""Worker: a Skydeck publisher or subscriber node of PoseStamped on /bench/pose (the subscriber
reads any topic and type given with ``--topic`` and ``--type``).

    python -m benchmarks.topic_skydeck sub --mode latency      # READY, then RESULT on `stop`
    python -m benchmarks.topic_skydeck pub --mode latency --rate 1000 --duration 2

Both are ordinary nodes (``create_publisher`` / ``create_subscription``) registered with the
core at ``SKYDECK_CORE_URL``; the subscriber links to the publisher the way every node does.
The publisher waits for ``--subscribers`` readers, then publishes as fast as it can
(throughput: it yields to the event loop after every ``BURST`` messages, as the bare publisher does) or at
``--rate`` with the send time in ``header.stamp`` (latency).
"""

from __future__ import annotations

import argparse
import asyncio
import inspect
import time
from collections.abc import Callable
from typing import Any

from benchmarks.payload import BURST, TOPIC, pose_message, stamp_now
from benchmarks.sink import Sink, emit, topic_arguments, wait_for_stop_async
from services.runtime import Node, NodeSettings
from services.runtime.executor import run
from shared_models import Message, get_interface
from shared_models.geometry_msgs import PoseStamped

_QUEUE = 100
_SUBSCRIBERS_TIMEOUT_S = 30.0
_DRAIN_S = 0.3  # after the last publish, let outboxes reach the sockets before stopping


async def paced(rate_hz: float, duration_s: float, send: Callable[[], object]) -> int:
    """Call ``send()`` at ``rate_hz`` for ``duration_s`` (catching up if late); returns the count.

    ``send`` may be a coroutine function; it is awaited then.
    """
    period_s = 1.0 / rate_hz
    start = time.monotonic()
    sent = 0
    while True:
        now = time.monotonic()
        if now - start >= duration_s:
            return sent
        due = start + sent * period_s
        if due > now:
            await asyncio.sleep(due - now)
        if inspect.isawaitable(result := send()):
            await result
        sent += 1


async def publisher(args: argparse.Namespace) -> None:
    node = Node("bench_pub", settings=NodeSettings(port=args.port))
    pub = node.create_publisher(PoseStamped, TOPIC, _QUEUE)
    await node.start()
    try:
        async with asyncio.timeout(_SUBSCRIBERS_TIMEOUT_S):
            while pub.get_subscription_count() < args.subscribers:
                await asyncio.sleep(0.01)
        msg = pose_message(args.size)
        emit("READY", {"url": node.url})
        cpu_start, start = time.process_time(), time.monotonic()
        if args.mode == "throughput":
            end = start + args.duration
            sent = 0
            publish = pub.publish
            while time.monotonic() < end:
                publish(msg)
                sent += 1
                if sent % BURST == 0:
                    await asyncio.sleep(0)
        else:
            stamp = msg.header.stamp

            def send() -> None:
                stamp_now(stamp)
                pub.publish(msg)

            sent = await paced(args.rate, args.duration, send)
        wall_s, cpu_s = time.monotonic() - start, time.process_time() - cpu_start
        await asyncio.sleep(_DRAIN_S)
        emit("RESULT", {"sent": sent, "wall_s": wall_s, "cpu_s": cpu_s, "rate": sent / wall_s})
    finally:
        await node.stop()


async def subscriber(args: argparse.Namespace) -> None:
    node = Node("bench_sub", settings=NodeSettings(port=args.port))
    sink = Sink(args.mode, args.warmup)
    if args.mode == "latency":

        def on_message(msg: Any) -> None:
            sink.arrive(msg.header.stamp.sec, msg.header.stamp.nanosec)

    else:

        def on_message(msg: Any) -> None:
            sink.arrive()

    msg_type = get_interface(args.type)
    if not (isinstance(msg_type, type) and issubclass(msg_type, Message)):
        raise SystemExit(f"--type {args.type} is a service, not a message")
    node.create_subscription(msg_type, args.topic, on_message, _QUEUE)
    await node.start()
    try:
        emit("READY", {"url": node.url})
        await wait_for_stop_async()
        emit("RESULT", sink.summary())
    finally:
        await node.stop()


def main() -> None:
    args = topic_arguments(__doc__.splitlines()[0]).parse_args()
    run(publisher(args) if args.role == "pub" else subscriber(args))


if __name__ == "__main__":
    main()
