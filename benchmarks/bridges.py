"""The rosbridge endpoint against the core's native stream: throughput and round trip.

Both are measured through one core, with the same bare ``websockets`` client
(:mod:`benchmarks.bridge_client`): throughput from a Skydeck publisher node to the client
(each frame parsed, as a client does), and the round trip of a stamped message the client
publishes, echoed by a node and read back (what rosbridge_suite's published 41.5 ms measures).
"""

from __future__ import annotations

from typing import Any

from benchmarks.processes import BenchError, Worker, worker_env
from benchmarks.topics import CoreHolder, pair_results

__all__ = ["ROSBRIDGE_RTT_MS", "run_bridge_rtt", "run_bridge_throughput"]

ROSBRIDGE_RTT_MS = 41.5  # rosbridge_suite's published round trip
_READY_TIMEOUT_S = 30.0


def _client_url(core: CoreHolder, via: str) -> str:
    core_url = core.get()
    return core.rosbridge_url if via == "rosbridge" else core_url.replace("http://", "ws://")


def run_bridge_throughput(via: str, core: CoreHolder, *, duration_s: float) -> dict[str, Any]:
    """Messages/s a client reads through ``via`` ("native" or "rosbridge") from a node
    publishing as fast as it can."""
    url = _client_url(core, via)
    env = worker_env(core.url)
    workers: list[Worker] = []
    try:
        sub = Worker(f"bridge-{via}-sub", "benchmarks.bridge_client", "sub", "--via", via, "--url", url, env=env)
        workers.append(sub)
        sub.expect("READY", _READY_TIMEOUT_S)
        pub = Worker(f"bridge-{via}-pub", "benchmarks.topic_skydeck", "pub", "--mode", "throughput",
                     "--duration", str(duration_s), env=env)  # fmt: skip
        workers.append(pub)
        pub.expect("READY", _READY_TIMEOUT_S)
        published, received = pair_results(pub, sub, duration_s, what=f"the {via} client")
        return {**received, "publisher_rate": published["rate"], "delivered": received["received"] / published["sent"]}
    finally:
        for worker in reversed(workers):
            worker.stop()


def run_bridge_rtt(via: str, core: CoreHolder, *, duration_s: float, rate_hz: float) -> dict[str, Any]:
    """Round trips of stamped messages a client publishes through ``via`` and reads back."""
    url = _client_url(core, via)
    env = worker_env(core.url)
    with Worker(f"bridge-{via}-echo", "benchmarks.bridge_client", "echo", env=env) as echo:
        echo.expect("READY", _READY_TIMEOUT_S)
        with Worker(f"bridge-{via}-rtt", "benchmarks.bridge_client", "rtt", "--via", via, "--url", url,
                    "--rate", str(rate_hz), "--duration", str(duration_s), env=env) as client:  # fmt: skip
            result = client.expect("RESULT", duration_s + 30.0)
        echo.send("stop")
    if result["received"] < 2:
        raise BenchError(f"the {via} client got {result['received']} of {result['sent']} round trips back")
    return result
