"""The soak: memory stays flat under a busy classroom for as long as it runs.

    skydeck bench --soak 10          # minutes; not part of the default or CI runs

The drone world runs at ``--speed max`` under ``skydeck launch``; against it, 50 viewers read
``/drone/pose`` through the core, one reader stalls (it reads nothing; a new one replaces it
every minute), and a reconnecting client opens and closes a socket every few hundred milliseconds.
Every process's RSS (the core and each node) is sampled every few seconds; the first fifth of
the run is warm-up. The result: each process's RSS at the end against its value after warm-up
(within 10% passes) and the slope of a least-squares line through the samples (MiB/minute);
the row ``soak_rss_slope`` is the slope of the process whose line grows most over the run as a
share of its RSS (passes under 10%).
"""

from __future__ import annotations

import asyncio
import contextlib
import statistics
import sys
import threading
import time
from pathlib import Path
from typing import Any

from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from benchmarks.processes import BenchError, Worker, worker_env
from benchmarks.report import Result
from services.runtime.edge.links import stream_url
from services.runtime.ports import free_port_block

__all__ = ["run_soak"]

_VIEWERS = 50
_SAMPLE_EVERY_S = 5.0
_WARMUP_FRACTION = 0.2
_READY_TIMEOUT_S = 90.0


def _rss_mib(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


async def _clients(core_url: str, stop: threading.Event, counters: dict[str, int]) -> None:
    async def viewer() -> None:
        while not stop.is_set():
            try:
                async with connect(stream_url(core_url, "/drone/pose"), max_size=None) as websocket:
                    async for _ in websocket:
                        counters["frames"] += 1
                        if stop.is_set():
                            return
            except OSError:
                await asyncio.sleep(0.5)

    async def stalled() -> None:
        # Reads nothing: the core sheds its frames (its queue), then gives up on it (4001 once its
        # socket is full, or the keepalive); a new one replaces it every minute.
        while not stop.is_set():
            with contextlib.suppress(OSError, ConnectionClosed):
                async with connect(stream_url(core_url, "/drone/pose"), max_queue=1, max_size=None):
                    counters["stalled_readers"] += 1
                    for _ in range(120):
                        if stop.is_set():
                            return
                        await asyncio.sleep(0.5)

    async def reconnecting() -> None:
        while not stop.is_set():
            try:
                async with connect(stream_url(core_url, "/drone/pose")) as websocket:
                    await websocket.recv()
                    counters["reconnects"] += 1
            except OSError:
                pass
            await asyncio.sleep(0.3)

    tasks = [asyncio.create_task(viewer()) for _ in range(_VIEWERS)]
    tasks += [asyncio.create_task(stalled()), asyncio.create_task(reconnecting())]
    while not stop.is_set():
        await asyncio.sleep(0.2)
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)


def _slope_mib_per_min(samples: list[tuple[float, float]]) -> float:
    if len(samples) < 2:
        return 0.0
    times = [t / 60 for t, _ in samples]
    values = [v for _, v in samples]
    return statistics.linear_regression(times, values).slope


def run_soak(minutes: float) -> tuple[list[Result], dict[str, Any]]:
    """Run the soak for ``minutes``; rows (one per process, and the whole) and the samples."""
    if not minutes > 0:
        raise ValueError(f"--soak needs a positive number of minutes, got {minutes}")
    base = free_port_block(5)
    core_url = f"http://127.0.0.1:{base}"
    argv = [sys.executable, "-m", "services.cli", "launch", "--base-port", str(base), "--speed", "max", "--seed", "1"]
    launch = Worker("soak-launch", argv=argv, env=worker_env(core_url))
    try:
        launch.wait_for_line("[launch] all", _READY_TIMEOUT_S)
        pids = _node_pids(core_url)
        stop = threading.Event()
        counters = {"frames": 0, "stalled_readers": 0, "reconnects": 0}
        clients = threading.Thread(target=lambda: asyncio.run(_clients(core_url, stop, counters)), daemon=True)
        clients.start()
        duration_s = minutes * 60
        started = time.monotonic()
        samples: dict[str, list[tuple[float, float]]] = {name: [] for name in pids}
        while (elapsed := time.monotonic() - started) < duration_s:
            if launch.returncode is not None:
                raise BenchError(f"skydeck launch exited during the soak:\n{launch.tail(15)}")
            for name, pid in pids.items():
                samples[name].append((elapsed, _rss_mib(pid)))
            time.sleep(min(_SAMPLE_EVERY_S, max(duration_s - elapsed, 0.1)))
        stop.set()
        clients.join(10)
    finally:
        launch.stop(timeout_s=15.0)
    return _summarise(samples, duration_s, counters), {"rss": samples, "counters": counters}


def _node_pids(core_url: str) -> dict[str, int]:
    import httpx

    graph = httpx.get(core_url + "/api/graph", timeout=5).json()
    return _one_name_per_process(graph["nodes"])


def _one_name_per_process(nodes: list[dict[str, Any]]) -> dict[str, int]:
    """A name for each process of the graph: the core's nodes (/rosapi, ...) share its process,
    which is measured once, as /skydeck_core; a process hosting several other nodes, by the first."""
    names: dict[int, str] = {}
    for node in nodes:
        if node["name"] == "/skydeck_core" or node["pid"] not in names:
            names[node["pid"]] = node["name"]
    return {name: pid for pid, name in names.items()}


def _summarise(samples: dict[str, list[tuple[float, float]]], duration_s: float, counters: dict[str, int]) -> list[Result]:
    results = []
    warm_s = duration_s * _WARMUP_FRACTION
    fits: list[tuple[float, str, float, float]] = []  # (fitted growth over the run, process, slope, RSS)
    for name, points in samples.items():
        warm = [(t, v) for t, v in points if t >= warm_s]
        if not warm:
            continue
        after_warmup, end = warm[0][1], warm[-1][1]
        growth = end / after_warmup
        slope = _slope_mib_per_min(warm)
        results.append(
            Result(f"soak_rss{name.replace('/', '_')}", end, "MiB", reference="after warm-up", reference_value=after_warmup,
                   target="within 10%", met=0.9 <= growth <= 1.1,
                   detail={"slope_mib_per_min": slope, "samples": len(points), **counters})
        )  # fmt: skip
        fits.append((slope * (warm[-1][0] - warm[0][0]) / 60 / after_warmup, name, slope, after_warmup))
    if fits:
        fitted_growth, name, slope, rss = max(fits)
        results.append(
            Result("soak_rss_slope", slope, "MiB/min", reference=f"{name} after warm-up (MiB)", reference_value=rss,
                   target="the steepest process grows < 10% over the run (fitted line)", met=fitted_growth < 0.1,
                   detail={"process": name, "fitted_growth": fitted_growth,
                           "slopes_mib_per_min": {r.name: r.detail["slope_mib_per_min"] for r in results}})
        )  # fmt: skip
    return results
