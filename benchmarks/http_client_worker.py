"""Worker: what an HTTP client costs a process per call (a keep-alive ``POST`` and its reply).

    python -m benchmarks.http_client_worker internal URL --calls 2000   # RESULT {"cpu_us", "wall_us"}
    python -m benchmarks.http_client_worker httpx URL --calls 2000      # httpx.AsyncClient
    python -m benchmarks.http_client_worker httpx-sync URL --calls 2000 # httpx.Client (the CLI's)

In a process of its own, so that its CPU time is the client's alone (the server is another
process). Skydeck's processes call each other with ``internal``
(:mod:`services.runtime.http_client`); the CLI calls the core with httpx.
"""

from __future__ import annotations

import argparse
import asyncio
import time
from collections.abc import Awaitable, Callable

import httpx

from benchmarks.processes import BenchError
from benchmarks.sink import emit
from services.runtime.executor import run
from services.runtime.http_client import HttpClient

_BODY = b"{}"
_HEADERS = {"content-type": "application/json"}
_WARMUP_CALLS = 50


def _checked(status: int, url: str) -> None:
    if status != 200:
        raise BenchError(f"POST {url} answered {status}")


async def _timed(call: Callable[[], Awaitable[int]], url: str, calls: int) -> dict[str, float]:
    for _ in range(_WARMUP_CALLS):
        _checked(await call(), url)
    cpu, wall = time.process_time(), time.perf_counter()
    for _ in range(calls):
        _checked(await call(), url)
    return {"cpu_us": (time.process_time() - cpu) * 1e6 / calls, "wall_us": (time.perf_counter() - wall) * 1e6 / calls}


async def _internal(url: str, calls: int) -> dict[str, float]:
    client = HttpClient()

    async def call() -> int:
        return (await client.post(url, _BODY, headers=_HEADERS, timeout_s=10.0)).status

    try:
        return await _timed(call, url, calls)
    finally:
        await client.aclose()


async def _httpx(url: str, calls: int) -> dict[str, float]:
    async with httpx.AsyncClient(timeout=10.0) as client:

        async def call() -> int:
            return (await client.post(url, content=_BODY, headers=_HEADERS)).status_code

        return await _timed(call, url, calls)


def _httpx_sync(url: str, calls: int) -> dict[str, float]:
    with httpx.Client(timeout=10.0) as client:

        async def call() -> int:  # the calls block, as the CLI's do; the loop only counts them
            return client.post(url, content=_BODY, headers=_HEADERS).status_code

        return asyncio.run(_timed(call, url, calls))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("client", choices=["internal", "httpx", "httpx-sync"])
    parser.add_argument("url")
    parser.add_argument("--calls", type=int, default=2000)
    args = parser.parse_args()
    if args.client == "httpx-sync":
        result = _httpx_sync(args.url, args.calls)
    else:
        result = run(_internal(args.url, args.calls) if args.client == "internal" else _httpx(args.url, args.calls))
    emit("RESULT", result)


if __name__ == "__main__":
    main()
