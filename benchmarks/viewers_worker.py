"""Worker: a classroom on one core. A publisher node of poses and camera images, and many viewers.

    python -m benchmarks.viewers_worker publisher --size 640x480 --image-hz 30   # READY, RESULT on stop
    python -m benchmarks.viewers_worker viewers --core URL --pose 100 --image 20  # READY, RESULT on stop

The publisher is an ordinary node: ``/bench/pose`` (PoseStamped, 60 Hz), ``/bench/image``
(sensor_msgs/Image, raw rgb8) and ``/bench/image/compressed`` (CompressedImage, JPEG), each
stamped with the machine-wide monotonic clock when published. The viewers read them through
the core, as browsers do: pose viewers in JSON, image viewers in msgpack (binary frames; a raw
image is 0.9 MB). A viewer may also stall: it opens its socket and never reads.
"""

from __future__ import annotations

import argparse
import asyncio
import io
import json
import time
from typing import Any

import ormsgpack
from websockets.asyncio.client import ClientConnection, connect

from benchmarks.payload import latency_us, stamp_now
from benchmarks.sink import counting_window, emit, percentile, wait_for_stop_async
from services.runtime import Node, NodeSettings
from services.runtime.edge.links import stream_url
from services.runtime.executor import run
from shared_models.geometry_msgs import PoseStamped
from shared_models.sensor_msgs import CompressedImage, Image

POSE, IMAGE, JPEG = "/bench/pose", "/bench/image", "/bench/image/compressed"
_POSE_HZ = 60.0


def _image(width: int, height: int) -> tuple[Image, CompressedImage]:
    from PIL import Image as Picture

    gradient = bytes((x * 255 // max(width - 1, 1)) for _ in range(height) for x in range(width) for _ in range(3))
    raw = Image(height=height, width=width, encoding="rgb8", step=width * 3, data=gradient)
    buffer = io.BytesIO()
    Picture.frombytes("RGB", (width, height), gradient).save(buffer, format="JPEG", quality=80)
    return raw, CompressedImage(format="jpeg", data=buffer.getvalue())


async def publisher(args: argparse.Namespace) -> None:
    width, height = (int(part) for part in args.size.split("x"))
    node = Node("bench_camera", settings=NodeSettings(port=0))
    poses = node.create_publisher(PoseStamped, POSE, 10)
    images = node.create_publisher(Image, IMAGE, 2)
    jpegs = node.create_publisher(CompressedImage, JPEG, 2)
    raw, jpeg = _image(width, height)
    counts = {POSE: 0, IMAGE: 0, JPEG: 0}

    async def every(period_s: float, publish: Any) -> None:
        next_at = time.monotonic()
        while True:
            publish()
            next_at += period_s
            await asyncio.sleep(max(0.0, next_at - time.monotonic()))

    def pose() -> None:
        msg = PoseStamped()
        stamp_now(msg.header.stamp)
        poses.publish(msg)
        counts[POSE] += 1

    def image() -> None:
        # A new header each time (the data is shared): each message has its own stamp.
        frame = raw.model_copy(update={"header": raw.header.model_copy(deep=True)})
        stamp_now(frame.header.stamp)
        images.publish(frame)
        compressed = jpeg.model_copy(update={"header": jpeg.header.model_copy(deep=True)})
        stamp_now(compressed.header.stamp)
        jpegs.publish(compressed)
        counts[IMAGE] += 1
        counts[JPEG] += 1

    await node.start()
    tasks = [asyncio.create_task(every(1 / _POSE_HZ, pose)), asyncio.create_task(every(1 / args.image_hz, image))]
    emit("READY", {"url": node.url})
    started_cpu, started = time.process_time(), time.monotonic()
    await wait_for_stop_async()
    for task in tasks:
        task.cancel()
    wall = time.monotonic() - started
    emit("RESULT", {"published": counts, "wall_s": wall, "cpu": (time.process_time() - started_cpu) / wall})
    await node.stop()


class _Viewer:
    def __init__(self, url: str, binary: bool, stalled: bool) -> None:
        self.url, self.binary, self.stalled = url, binary, stalled
        self.received = 0
        self.latencies_us: list[float] = []
        self.close_code: int | None = None

    async def run(self, counting: asyncio.Event) -> None:
        options: dict[str, Any] = {"max_size": None}
        if self.binary:
            options["subprotocols"] = ["skydeck.msgpack"]
        if self.stalled:
            options["max_queue"] = 1
        async with connect(self.url, **options) as websocket:
            if self.stalled:
                await _never_read(websocket)
                return
            async for frame in websocket:
                if not counting.is_set():
                    continue
                message = ormsgpack.unpackb(frame) if isinstance(frame, bytes) else json.loads(frame)
                stamp = message["header"]["stamp"]
                self.received += 1
                self.latencies_us.append(latency_us(stamp["sec"], stamp["nanosec"]))


async def _never_read(websocket: ClientConnection) -> None:
    await asyncio.Event().wait()  # holds the socket open, reading nothing, until cancelled


async def viewers(args: argparse.Namespace) -> None:
    crowd = [_Viewer(stream_url(args.core, POSE), False, False) for _ in range(args.pose)]
    crowd += [_Viewer(stream_url(args.core, args.image_topic), True, False) for _ in range(args.image)]
    crowd += [_Viewer(stream_url(args.core, args.image_topic, queue=2), True, True) for _ in range(args.stalled)]
    counting = asyncio.Event()
    wall = await counting_window([asyncio.create_task(viewer.run(counting)) for viewer in crowd], counting, args.warmup)

    def summary(group: list[_Viewer]) -> dict[str, Any]:
        latencies = sorted(value for viewer in group for value in viewer.latencies_us)
        return {
            "viewers": len(group),
            "rates": [viewer.received / wall for viewer in group],
            "p50_us": percentile(latencies, 0.5),
            "p99_us": percentile(latencies, 0.99),
        }

    emit("RESULT", {"pose": summary(crowd[: args.pose]), "image": summary(crowd[args.pose : args.pose + args.image]), "wall_s": wall})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("role", choices=["publisher", "viewers"])
    parser.add_argument("--size", default="640x480", help="publisher: image size WxH")
    parser.add_argument("--image-hz", type=float, default=30.0)
    parser.add_argument("--core", default="", help="viewers: the core's URL")
    parser.add_argument("--pose", type=int, default=100, help="viewers of /bench/pose (JSON)")
    parser.add_argument("--image", type=int, default=20, help="viewers of --image-topic (msgpack)")
    parser.add_argument("--image-topic", default=IMAGE)
    parser.add_argument("--stalled", type=int, default=0, help="viewers that never read")
    parser.add_argument("--warmup", type=float, default=1.0)
    args = parser.parse_args()
    run(publisher(args) if args.role == "publisher" else viewers(args))


if __name__ == "__main__":
    main()
