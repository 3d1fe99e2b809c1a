"""Worker: a client of the core reading or echoing through one of its endpoints.

    python -m benchmarks.bridge_client sub --via rosbridge --url ws://127.0.0.1:PORT
    python -m benchmarks.bridge_client rtt --via native --url ws://127.0.0.1:CORE --rate 1000
    python -m benchmarks.bridge_client echo                  # a node: /bench/ping -> /bench/pong

``sub`` counts PoseStamped frames from ``/bench/pose`` (published by a Skydeck node) as a
client does: each frame parsed (``json.loads``), through the native stream ``ws://CORE/TOPIC``
or the rosbridge endpoint (a ``subscribe`` op, ``publish`` envelopes). ``rtt`` publishes
stamped pings through the same endpoint at ``--rate`` and reads the ``echo`` node's pongs back:
the round trip rosbridge users measure. Both are bare ``websockets`` clients, so the two
endpoints differ only in the protocol the core speaks.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import time
from typing import Any

from websockets.asyncio.client import ClientConnection, connect

from benchmarks.payload import TOPIC, frame_template, latency_us
from benchmarks.sink import Sink, emit, percentile, wait_for_stop_async
from benchmarks.topic_skydeck import paced

PING, PONG = "/bench/ping", "/bench/pong"
_POSE = "geometry_msgs/msg/PoseStamped"
_QUEUE = 100


async def _open(via: str, url: str, topic: str, *, mode: str = "subscribe") -> ClientConnection:
    """A socket reading (or, ``mode="publish"``, publishing) ``topic`` through ``via``."""
    if via == "native":
        query = "?mode=publish&type=" + _POSE if mode == "publish" else f"?mode=subscribe&queue={_QUEUE}"
        return await connect(url + topic + query, max_size=None)
    websocket = await connect(url, max_size=None)
    if mode == "publish":
        await websocket.send(json.dumps({"op": "advertise", "topic": topic, "type": _POSE}))
    else:
        await websocket.send(json.dumps({"op": "subscribe", "topic": topic, "type": _POSE, "queue_length": _QUEUE}))
    return websocket


def _message(via: str, frame: str | bytes) -> dict[str, Any]:
    parsed: dict[str, Any] = json.loads(frame)
    return parsed if via == "native" else parsed["msg"]


async def subscriber(args: argparse.Namespace) -> None:
    sink = Sink("throughput", args.warmup)
    websocket = await _open(args.via, args.url, TOPIC)

    async def read() -> None:
        async for frame in websocket:
            _message(args.via, frame)
            sink.arrive()

    reader = asyncio.create_task(read())
    emit("READY", {})
    await wait_for_stop_async()
    reader.cancel()
    emit("RESULT", sink.summary())
    await websocket.close()


async def round_trips(args: argparse.Namespace) -> None:
    template = frame_template()
    pongs = await _open(args.via, args.url, PONG)
    pings = await _open(args.via, args.url, PING, mode="publish")
    samples: list[float] = []
    started = time.monotonic()

    async def read() -> None:
        async for frame in pongs:
            stamp = _message(args.via, frame)["header"]["stamp"]
            if time.monotonic() - started >= args.warmup:
                samples.append(latency_us(stamp["sec"], stamp["nanosec"]))

    reader = asyncio.create_task(read())
    await asyncio.sleep(1.0)  # the echo node links to the new publisher

    async def ping() -> None:
        sec, nanosec = divmod(time.monotonic_ns(), 1_000_000_000)
        frame = template % (0, sec, nanosec)
        if args.via == "native":
            await pings.send(frame)
        else:
            await pings.send('{"op":"publish","topic":"' + PING + '","msg":' + frame + "}")

    sent = await paced(args.rate, args.duration, ping)
    await asyncio.sleep(0.3)
    reader.cancel()
    await pings.close()
    await pongs.close()
    values = sorted(samples)
    emit("RESULT", {
        "sent": sent,
        "received": len(samples),
        "p50_us": percentile(values, 0.5),
        "p99_us": percentile(values, 0.99),
    })


async def echo(args: argparse.Namespace) -> None:
    from services.runtime import Node, NodeSettings
    from shared_models.geometry_msgs import PoseStamped

    node = Node("bench_echo", settings=NodeSettings(port=0))
    pong = node.create_publisher(PoseStamped, PONG, _QUEUE)
    node.create_subscription(PoseStamped, PING, pong.publish, _QUEUE)
    await node.start()
    try:
        emit("READY", {"url": node.url})
        await wait_for_stop_async()
    finally:
        await node.stop()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("role", choices=["sub", "rtt", "echo"])
    parser.add_argument("--via", choices=["native", "rosbridge"], default="native")
    parser.add_argument("--url", default="", help="ws://HOST:PORT of the core (native) or the endpoint")
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--duration", type=float, default=2.0)
    parser.add_argument("--warmup", type=float, default=0.3)
    args = parser.parse_args()
    role = {"sub": subscriber, "rtt": round_trips, "echo": echo}[args.role]
    asyncio.run(role(args))


if __name__ == "__main__":
    main()
