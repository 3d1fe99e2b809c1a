"""Skydeck's own HTTP client against httpx: why the product has two (docs/architecture.md).

Per call: a client process POSTs to a bare FastAPI endpoint (:mod:`benchmarks.service_worker`)
over one kept-alive connection and reports the CPU time it spent per call
(:mod:`benchmarks.http_client_worker`): what a Skydeck process pays for each call it forwards
or makes. One-shot: a fresh ``python -c`` imports the client and makes one call, as each CLI
command does, timed from spawn to exit (the interpreter's own start-up included, the same for
both).
"""

from __future__ import annotations

import subprocess
import sys
import time
from typing import Any

from benchmarks.processes import BenchError, Worker, worker_env
from benchmarks.service_worker import SERVICE

__all__ = ["ClientTargets"]

_READY_TIMEOUT_S = 30.0
_ONE_SHOT = {
    "httpx": "import httpx; r = httpx.post({url!r}, content=b'{{}}', headers={{'content-type': 'application/json'}}, timeout=10); assert r.status_code == 200",
    "internal": (
        "import asyncio; from services.runtime.http_client import HttpClient\n"
        "async def main():\n"
        "    client = HttpClient(); r = await client.post({url!r}, b'{{}}', timeout_s=10); await client.aclose(); return r\n"
        "assert asyncio.run(main()).status == 200"
    ),
}


class ClientTargets:
    """The endpoint the clients call, started once for the family's trials."""

    def __init__(self) -> None:
        self._server: Worker | None = None
        self.url = ""

    def start(self) -> None:
        self._server = Worker("http-clients-server", "benchmarks.service_worker", "fastapi", env=worker_env())
        self.url = self._server.expect("READY", _READY_TIMEOUT_S)["url"] + SERVICE

    def close(self) -> None:
        if self._server is not None:
            self._server.stop()
            self._server = None

    def per_call(self, client: str, calls: int) -> dict[str, Any]:
        """CPU and wall microseconds per call of ``client`` (internal, httpx, httpx-sync)."""
        if self._server is None:
            self.start()
        with Worker(f"http-client-{client}", "benchmarks.http_client_worker", client, self.url, "--calls", str(calls)) as worker:
            return worker.expect("RESULT", 120.0)

    def one_shot(self, client: str) -> dict[str, Any]:
        """Milliseconds from spawning a process to its exit after one call with ``client``."""
        if self._server is None:
            self.start()
        started = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-c", _ONE_SHOT[client].format(url=self.url)], capture_output=True, text=True, timeout=60
        )
        took_ms = (time.perf_counter() - started) * 1000
        if done.returncode != 0:
            raise BenchError(f"one call with {client} failed: {done.stderr.strip().splitlines()[-1:]}")
        return {"ms": took_ms}
