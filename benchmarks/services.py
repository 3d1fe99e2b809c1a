"""Service round trips: a Trigger call to a node directly, through the core's gateway, and to a
bare FastAPI endpoint, all from the same HTTP client.

The client is one ``httpx.Client`` (keep-alive, as the SDK's clients and the CLI use httpx)
in the benchmark's own process; each server is a worker process. Every trial makes a few
warm-up calls, then times sequential calls with ``perf_counter``.
"""

from __future__ import annotations

import time
from typing import Any

import httpx

from benchmarks.processes import BenchError, Worker, worker_env
from benchmarks.service_worker import SERVICE
from benchmarks.sink import percentile
from benchmarks.topics import CoreHolder

__all__ = ["ServiceTargets"]

_WARMUP_CALLS = 50
_BODY = b"{}"
_HEADERS = {"Content-Type": "application/json"}


class ServiceTargets:
    """The three servers of the service benchmark, started once and called trial after trial."""

    def __init__(self, core: CoreHolder) -> None:
        self._core = core
        self._workers: list[Worker] = []
        self.urls: dict[str, str] = {}
        self._client: httpx.Client | None = None

    def start(self) -> None:
        core_url = self._core.get()
        for kind in ("skydeck", "fastapi"):
            worker = Worker(f"service-{kind}", "benchmarks.service_worker", kind, env=worker_env(core_url))
            self._workers.append(worker)
            self.urls[kind] = worker.expect("READY", 30.0)["url"]
        self.urls["gateway"] = core_url
        self._client = httpx.Client(timeout=10.0)

    def close(self) -> None:
        if self._client is not None:
            self._client.close()
        for worker in self._workers:
            worker.stop()
        self._workers.clear()

    def measure(self, target: str, calls: int) -> dict[str, Any]:
        """``calls`` timed round trips to ``target`` (skydeck, gateway or fastapi), in microseconds."""
        if self._client is None:
            self.start()
        client = self._client
        if client is None:
            raise BenchError("the service benchmark's client did not start")
        url = self.urls[target] + SERVICE
        for _ in range(_WARMUP_CALLS):
            _call(client, url)
        timings: list[float] = []
        clock = time.perf_counter
        for _ in range(calls):
            start = clock()
            _call(client, url)
            timings.append((clock() - start) * 1e6)
        timings.sort()
        return {
            "p50_us": percentile(timings, 0.5),
            "p99_us": percentile(timings, 0.99),
            "mean_us": sum(timings) / len(timings),
            "calls": calls,
        }


def _call(client: httpx.Client, url: str) -> None:
    reply = client.post(url, content=_BODY, headers=_HEADERS)
    if reply.status_code != 200 or not reply.json().get("success"):
        raise BenchError(f"POST {url} answered {reply.status_code}: {reply.text[:200]}")
