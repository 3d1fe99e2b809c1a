"""Worker: a class's readers, beside the class's world (``benchmarks.classroom``).

    python -m benchmarks.classroom_worker nodes --students s01,s02        # READY, RESULT on stop
    python -m benchmarks.classroom_worker dashboards --core URL --tokens FILE

``nodes``: the students' programs as the world sees them: one node (the class's process token)
subscribed to every student's ``scan``, ``odom`` and ``bump``, counting what arrives, as thirty
wall followers would read them (one process stands in for thirty: the bench has two cores).

``dashboards``: each student's browser through the core with their own token, at the rates the
dashboard asks for (``odom`` 20 Hz, ``scan`` 5 Hz, ``bump`` 10 Hz: web_ui/static/js/room.js),
and the instructor's class page (``/simulator/robots`` at 10 Hz, ``GET /api/class`` every
second). RESULT: every reader's rate, by topic kind, and the class page's request times.
"""

from __future__ import annotations

import argparse
import asyncio
import csv
import time
from pathlib import Path
from typing import Any

import httpx
from websockets.asyncio.client import connect

from benchmarks.sink import counting_window, emit, percentile, wait_for_stop_async
from services.runtime import Node, NodeSettings
from services.runtime.edge.links import stream_url
from services.runtime.executor import run
from shared_models import Message
from shared_models.nav_msgs import Odometry
from shared_models.neato2_interfaces import Bump
from shared_models.sensor_msgs import LaserScan

DASHBOARD_RATES_HZ = {"odom": 20.0, "scan": 5.0, "bump": 10.0}
CLASS_VIEW_HZ = 10.0
_KINDS: dict[str, type[Message]] = {"scan": LaserScan, "odom": Odometry, "bump": Bump}


async def nodes(args: argparse.Namespace) -> None:
    node = Node("class_readers", settings=NodeSettings(port=0))
    counts: dict[str, int] = {}
    for student in args.students.split(","):
        for kind, msg_type in _KINDS.items():
            topic = f"/{student}/{kind}"
            counts[topic] = 0

            def arrive(msg: Any, topic: str = topic) -> None:
                counts[topic] += 1

            node.create_subscription(msg_type, topic, arrive, 10)
    await node.start()
    await asyncio.sleep(args.warmup)
    before = dict(counts)
    emit("READY", {})
    started = time.monotonic()
    await wait_for_stop_async()
    wall = time.monotonic() - started
    rates: dict[str, list[float]] = {kind: [] for kind in _KINDS}
    for topic, count in counts.items():
        rates[topic.rsplit("/", 1)[1]].append((count - before[topic]) / wall)
    emit("RESULT", {"rates": rates, "wall_s": wall})
    await node.stop()


class _Reader:
    def __init__(self, url: str) -> None:
        self.url = url
        self.received = 0
        self.closed: str | None = None

    async def run(self, counting: asyncio.Event) -> None:
        try:
            async with connect(self.url, max_size=None) as websocket:
                async for _ in websocket:
                    if counting.is_set():
                        self.received += 1
        except Exception as error:  # a refusal or a shed socket: said in the result
            self.closed = str(error)


async def _class_page(core: str, token: str, counting: asyncio.Event, times_ms: list[float]) -> None:
    async with httpx.AsyncClient(headers={"Authorization": f"Bearer {token}"}, timeout=10.0) as client:
        while True:
            started = time.perf_counter()
            reply = await client.get(core + "/api/class")
            reply.raise_for_status()
            if counting.is_set():
                times_ms.append(1000 * (time.perf_counter() - started))
            await asyncio.sleep(1.0)


async def dashboards(args: argparse.Namespace) -> None:
    with Path(args.tokens).open() as file:
        tokens = {row[0]: row[1] for row in csv.reader(file) if row and row[0] != "name"}
    readers: dict[str, list[_Reader]] = {kind: [] for kind in DASHBOARD_RATES_HZ}
    for student, token in tokens.items():
        if student == "instructor":
            continue
        for kind, rate in DASHBOARD_RATES_HZ.items():
            readers[kind].append(_Reader(stream_url(args.core, f"/{student}/{kind}", rate=rate, token=token)))
    truth = _Reader(stream_url(args.core, "/simulator/robots", rate=CLASS_VIEW_HZ, token=tokens["instructor"]))
    counting = asyncio.Event()
    page_ms: list[float] = []
    everyone = [reader for group in readers.values() for reader in group] + [truth]
    tasks = [asyncio.create_task(reader.run(counting)) for reader in everyone]
    tasks.append(asyncio.create_task(_class_page(args.core, tokens["instructor"], counting, page_ms)))
    wall = await counting_window(tasks, counting, args.warmup)
    page_ms.sort()
    emit("RESULT", {
        "rates": {kind: [r.received / wall for r in group] for kind, group in readers.items()},
        "class_view_rate": truth.received / wall,
        "closed": [r.closed for r in everyone if r.closed][:3],
        "class_page_p50_ms": percentile(page_ms, 0.5),
        "class_page_max_ms": page_ms[-1] if page_ms else 0.0,
        "wall_s": wall,
    })  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("role", choices=["nodes", "dashboards"])
    parser.add_argument("--students", default="", help="nodes: the students' names, comma-separated")
    parser.add_argument("--core", default="", help="dashboards: the core's URL")
    parser.add_argument("--tokens", default="", help="dashboards: the class's tokens file")
    parser.add_argument("--warmup", type=float, default=2.0)
    args = parser.parse_args()
    run(nodes(args) if args.role == "nodes" else dashboards(args))


if __name__ == "__main__":
    main()
