"""Worker: the reference pair, a bare ``websockets`` server (publisher) and client (subscriber).

    python -m benchmarks.topic_websockets pub --mode throughput   # READY {"port": P}
    python -m benchmarks.topic_websockets sub --port P            # RESULT on `stop`

The same JSON as Skydeck's PoseStamped, each frame made from a prepared template (Skydeck
serialises with pydantic) and decoded with ``json.loads`` (Skydeck validates into a
PoseStamped): the least an application can do with a message. No registry, no validation, no
queues: the limit of Python WebSockets on this machine.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import time

from websockets.asyncio.client import connect
from websockets.asyncio.server import ServerConnection, serve
from websockets.exceptions import ConnectionClosed

from benchmarks.payload import BURST, frame_template, stamped_frame
from benchmarks.sink import Sink, emit, topic_arguments, wait_for_stop_async
from benchmarks.topic_skydeck import paced

_MAX_SIZE = 1 << 20  # Skydeck's frame limit


async def publisher(args: argparse.Namespace) -> None:
    done: asyncio.Future[dict[str, float]] = asyncio.get_running_loop().create_future()
    template = frame_template(args.size)

    async def handler(websocket: ServerConnection) -> None:
        if done.done():
            return
        cpu_start, start = time.process_time(), time.monotonic()
        sent = 0
        try:
            if args.mode == "throughput":
                end = start + args.duration
                while time.monotonic() < end:
                    sent += 1
                    await websocket.send(template % (sent, 0, 0))
                    if sent % BURST == 0:
                        await asyncio.sleep(0)
            else:
                count = 0

                async def send() -> None:
                    nonlocal count
                    count += 1
                    await websocket.send(stamped_frame(template, count))

                sent = await paced(args.rate, args.duration, send)
        except ConnectionClosed:
            pass
        wall_s, cpu_s = time.monotonic() - start, time.process_time() - cpu_start
        await asyncio.sleep(0.3)
        if not done.done():
            done.set_result({"sent": sent, "wall_s": wall_s, "cpu_s": cpu_s, "rate": sent / wall_s})

    async with serve(handler, "127.0.0.1", args.port, compression=None, max_size=_MAX_SIZE) as server:
        port = next(iter(server.sockets)).getsockname()[1]
        emit("READY", {"port": port})
        emit("RESULT", await done)


async def subscriber(args: argparse.Namespace) -> None:
    sink = Sink(args.mode, args.warmup)
    latency = args.mode == "latency"
    loads = json.loads

    async def read() -> None:
        async with connect(
            f"ws://127.0.0.1:{args.port}/bench/pose", compression=None, max_size=_MAX_SIZE
        ) as websocket:
            try:
                async for frame in websocket:
                    data = loads(frame)
                    if latency:
                        stamp = data["header"]["stamp"]
                        sink.arrive(stamp["sec"], stamp["nanosec"])
                    else:
                        sink.arrive()
            except ConnectionClosed:
                pass

    reader = asyncio.create_task(read())
    emit("READY", {})
    await wait_for_stop_async()
    reader.cancel()
    emit("RESULT", sink.summary())


def main() -> None:
    args = topic_arguments(__doc__.splitlines()[0]).parse_args()
    asyncio.run(publisher(args) if args.role == "pub" else subscriber(args))


if __name__ == "__main__":
    main()
