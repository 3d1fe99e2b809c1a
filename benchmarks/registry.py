"""The registry under many nodes: N sessions register with a fresh core, in a chain of topics.

    python -m benchmarks.registry --nodes 200     # one RESULT line

Each session speaks the node session protocol (``services.runtime.protocol``) as a node does,
without serving anything: node *i* subscribes to ``/bench/reg/i`` and publishes
``/bench/reg/i+1``, so every registration changes the publishers of one topic that one other
node subscribes to. Measured: the wall time until every node is registered and has been told
the publishers of its topic, and the core's CPU time for it. Comparing 200 nodes with 20 says
whether the cost per node grows with the size of the graph (it did: every change re-told every
session about every subscription, O(n^2)).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
import time
from typing import Any

from websockets.asyncio.client import connect

from benchmarks.processes import start_core
from services.runtime.edge.links import stream_url
from services.runtime.protocol import Entity, NodeDescription, RegisterFrame

__all__ = ["measure_registry"]

_TYPE = "geometry_msgs/msg/PoseStamped"
_TIMEOUT_S = 120.0


def _description(index: int, count: int) -> NodeDescription:
    return NodeDescription(
        name=f"/bench_reg_{index}",
        url=f"http://127.0.0.1:1/reg{index}",  # never dialled: nobody reads these topics
        pid=index + 1,
        publications=[Entity(name=f"/bench/reg/{(index + 1) % count}", type=_TYPE)],
        subscriptions=[Entity(name=f"/bench/reg/{index}", type=_TYPE)],
    )


async def _session(core_url: str, index: int, count: int, told: asyncio.Event, hold: asyncio.Event) -> None:
    """Register node ``index``; set ``told`` once it knows a publisher of its topic; hold on."""
    async with connect(stream_url(core_url, "/api/session"), max_size=None) as websocket:
        await websocket.send(RegisterFrame(node=_description(index, count)).model_dump_json())
        async for raw in websocket:
            frame = json.loads(raw)
            if frame.get("op") == "publishers" and frame["publishers"]:
                told.set()
            if told.is_set() and hold.is_set():
                return


async def _register_all(core_url: str, count: int) -> float:
    told = [asyncio.Event() for _ in range(count)]
    hold = asyncio.Event()
    started = time.perf_counter()
    tasks = [asyncio.create_task(_session(core_url, i, count, told[i], hold)) for i in range(count)]
    try:
        async with asyncio.timeout(_TIMEOUT_S):
            await asyncio.gather(*(event.wait() for event in told))
        return time.perf_counter() - started
    finally:
        hold.set()
        for task in tasks:
            task.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)


def measure_registry(nodes: int) -> dict[str, Any]:
    """A fresh core; ``nodes`` sessions register at once; seconds and core CPU until all are told."""
    worker, url = start_core(f"registry-core-{nodes}")
    try:
        cpu_before = worker.cpu_seconds()
        seconds = asyncio.run(_register_all(url, nodes))
        cpu = worker.cpu_seconds() - cpu_before
    finally:
        worker.stop()
    return {"nodes": nodes, "seconds": seconds, "core_cpu_s": cpu, "core_cpu_ms_per_node": 1000 * cpu / nodes}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=200)
    args = parser.parse_args()
    sys.stdout.write("RESULT " + json.dumps(measure_registry(args.nodes)) + "\n")


if __name__ == "__main__":
    main()
