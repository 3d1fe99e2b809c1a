"""Topic benchmarks: one publisher -> one subscriber in separate processes, PoseStamped JSON.

Three transports, each a pair of worker processes spawned per trial: Skydeck nodes (through a
real core, the subscriber linking to the publisher as nodes do), the bare ``websockets``
server/client pair (the limit of Python WebSockets here), and zenoh (a peer users pick for
robot messaging). Throughput: the publisher sends as fast as it can for a fixed time and the
subscriber counts what arrives after a warm-up. Latency: 1,000 messages a second (latency,
not queueing) stamped with the machine-wide monotonic clock at publish, read in the callback.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from benchmarks.processes import BenchError, Worker, start_core, worker_env

__all__ = ["TRANSPORTS", "TopicRun", "pair_results", "run_topic_pair"]

TRANSPORTS = ("skydeck", "websockets", "zenoh")
_MODULES = {
    "skydeck": "benchmarks.topic_skydeck",
    "websockets": "benchmarks.topic_websockets",
    "zenoh": "benchmarks.topic_zenoh",
}
_READY_TIMEOUT_S = 30.0


@dataclass(frozen=True)
class TopicRun:
    """What one trial measured: the subscriber's summary and the publisher's."""

    subscriber: dict[str, Any]
    publisher: dict[str, Any]


class CoreHolder:
    """A Skydeck core started on first use and kept for the rest of a benchmark family (with
    its rosbridge endpoint on a free port if ``rosbridge``: ``rosbridge_url``)."""

    def __init__(self, *, rosbridge: bool = False) -> None:
        self._worker: Worker | None = None
        self._rosbridge = rosbridge
        self.url = ""
        self.rosbridge_url = ""

    def get(self) -> str:
        if self._worker is None:
            from benchmarks.processes import free_port

            port = free_port() if self._rosbridge else 0
            self._worker, self.url = start_core("bench-core", rosbridge_port=port)
            self.rosbridge_url = f"ws://127.0.0.1:{port}" if port else ""
        return self.url

    def cpu_seconds(self) -> float:
        """The core's CPU time so far (0 before it started)."""
        return self._worker.cpu_seconds() if self._worker is not None else 0.0

    def close(self) -> None:
        if self._worker is not None:
            self._worker.stop()
            self._worker = None


def run_topic_pair(
    transport: str,
    *,
    mode: str,
    duration_s: float,
    core: CoreHolder,
    rate_hz: float = 1000.0,
    size_bytes: int | None = None,
    warmup_s: float = 0.3,
) -> TopicRun:
    """Run one publisher/subscriber trial of ``transport`` and return both sides' results."""
    module = _MODULES[transport]
    flags = ["--mode", mode, "--duration", f"{duration_s}", "--rate", f"{rate_hz}", "--warmup", f"{warmup_s}"]
    if size_bytes is not None:
        flags += ["--size", str(size_bytes)]
    env = worker_env(core.get() if transport == "skydeck" else None)
    workers: list[Worker] = []
    try:
        if transport == "websockets":
            # The publisher is the server: it listens first and the subscriber connects to it.
            pub = Worker(f"{transport}-pub", module, "pub", *flags, env=env)
            workers.append(pub)
            port = pub.expect("READY", _READY_TIMEOUT_S)["port"]
            sub = Worker(f"{transport}-sub", module, "sub", *flags, "--port", str(port), env=env)
            workers.append(sub)
            sub.expect("READY", _READY_TIMEOUT_S)
        else:
            port_flags: list[str] = []
            if transport == "zenoh":
                from benchmarks.processes import free_port

                port_flags = ["--port", str(free_port())]
            sub = Worker(f"{transport}-sub", module, "sub", *flags, *port_flags, env=env)
            workers.append(sub)
            sub.expect("READY", _READY_TIMEOUT_S)
            pub = Worker(f"{transport}-pub", module, "pub", *flags, *port_flags, env=env)
            workers.append(pub)
            pub.expect("READY", _READY_TIMEOUT_S)
        published, received = pair_results(pub, sub, duration_s, what=f"{transport} subscriber")
        return TopicRun(received, published)
    finally:
        for worker in reversed(workers):
            worker.stop()


def pair_results(publisher: Worker, subscriber: Worker, duration_s: float, *, what: str) -> tuple[dict[str, Any], dict[str, Any]]:
    """A throughput pair's readings once the publisher is done: what it sent, and what the
    subscriber (``what``, for the error) received; BenchError when it received nearly nothing."""
    published = publisher.expect("RESULT", duration_s + 30.0)
    subscriber.send("stop")
    received = subscriber.expect("RESULT", 10.0)
    if received["counted"] < 2:
        raise BenchError(f"{what} received {received['received']} messages")
    return published, received
