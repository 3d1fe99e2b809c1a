"""Fan-out: one publisher node -> 100 subscriber nodes at 30 Hz, through a real core.

The subscribers are whole nodes (each with its server, core session and link), packed into a
few worker processes. The publisher waits until all of them are linked, publishes for a fixed
time at 30 Hz with the send time in the stamp, and reports its own CPU time; each subscriber
reports which sequence numbers it got. Delivered fraction = distinct messages received by all
subscribers / (subscribers x messages published).
"""

from __future__ import annotations

import statistics
from typing import Any

from benchmarks.processes import Worker, worker_env
from benchmarks.sink import percentile
from benchmarks.topics import CoreHolder

__all__ = ["run_fanout"]

_READY_TIMEOUT_S = 120.0


def run_fanout(
    core: CoreHolder, *, subscribers: int = 100, processes: int = 4, rate_hz: float = 30.0, duration_s: float = 3.0
) -> dict[str, Any]:
    """One fan-out trial: delivered fraction, publisher CPU (fraction of one core), latencies."""
    env = worker_env(core.get())
    counts = [subscribers // processes + (1 if i < subscribers % processes else 0) for i in range(processes)]
    workers: list[Worker] = []
    try:
        for index, count in enumerate(counts):
            workers.append(
                Worker(f"fanout-sub{index}", "benchmarks.fanout_worker", "--nodes", str(count), "--prefix", f"p{index}", env=env)
            )
        for worker in workers:
            worker.expect("READY", _READY_TIMEOUT_S)
        pub = Worker(
            "fanout-pub",
            "benchmarks.topic_skydeck",
            "pub",
            "--mode", "latency",
            "--rate", f"{rate_hz}",
            "--duration", f"{duration_s}",
            "--subscribers", str(subscribers),
            env=env,
        )  # fmt: skip
        workers.append(pub)
        pub.expect("READY", _READY_TIMEOUT_S)
        published = pub.expect("RESULT", duration_s + 30.0)
        distinct = 0
        latencies: list[float] = []
        for worker in workers[:-1]:
            worker.send("stop")
            result = worker.expect("RESULT", 20.0)
            distinct += sum(result["distinct"])
            latencies.extend(result["latencies_us"])
    finally:
        for worker in reversed(workers):
            worker.stop()
    latencies.sort()
    return {
        "delivered": distinct / (subscribers * published["sent"]),
        "published": published["sent"],
        "publisher_cpu": published["cpu_s"] / published["wall_s"],
        "latency_p50_us": percentile(latencies, 0.5),
        "latency_p99_us": percentile(latencies, 0.99),
        "latency_mean_us": statistics.fmean(latencies) if latencies else float("nan"),
    }
