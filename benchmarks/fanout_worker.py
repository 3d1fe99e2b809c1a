"""Worker: many Skydeck subscriber nodes of /bench/pose in one process (for the fan-out test).

    python -m benchmarks.fanout_worker --nodes 25 --prefix a    # READY, then RESULT on `stop`

Each node is a whole node (its own server, core session and link to the publisher), so 100
subscribers are 100 registered nodes and 100 sockets on the publisher, packed into a few
processes so that starting them does not dominate the run. Every node counts what it receives
and how long each message took from publish to its callback.
"""

from __future__ import annotations

import argparse
import asyncio

from benchmarks.payload import TOPIC, latency_us
from benchmarks.sink import emit, wait_for_stop_async
from services.runtime import Node, NodeSettings
from services.runtime.executor import run as run_loop
from shared_models.geometry_msgs import PoseStamped

_REGISTER_TIMEOUT_S = 60.0


class _Counter:
    def __init__(self) -> None:
        self.received = 0
        self.seqs: set[int] = set()
        self.latencies_us: list[float] = []

    def __call__(self, msg: PoseStamped) -> None:
        self.received += 1
        self.seqs.add(msg.header.seq)
        self.latencies_us.append(latency_us(msg.header.stamp.sec, msg.header.stamp.nanosec))


async def run(nodes: int, prefix: str) -> None:
    counters = [_Counter() for _ in range(nodes)]
    started: list[Node] = []
    try:
        for index, counter in enumerate(counters):
            node = Node(f"bench_fanout_{prefix}_{index}", settings=NodeSettings(port=0))
            node.create_subscription(PoseStamped, TOPIC, counter, 100)
            await node.start()
            started.append(node)
        async with asyncio.timeout(_REGISTER_TIMEOUT_S):
            for node in started:
                await node._session.registered.wait()  # type: ignore[union-attr]
        emit("READY", {})
        await wait_for_stop_async()
        emit(
            "RESULT",
            {
                "received": [c.received for c in counters],
                "distinct": [len(c.seqs) for c in counters],
                "latencies_us": [value for c in counters for value in c.latencies_us],
            },
        )
    finally:
        await asyncio.gather(*(node.stop() for node in started), return_exceptions=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=25)
    parser.add_argument("--prefix", default="a")
    args = parser.parse_args()
    run_loop(run(args.nodes, args.prefix))


if __name__ == "__main__":
    main()
