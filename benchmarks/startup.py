"""Startup and memory: ``skydeck launch`` to every node ready, and the whole system's RSS.

Ready means: every node of the workshop system (sim, perception, control, ai) answers
``/health`` and is in the core's ``/api/graph``. Memory is read from ``/proc`` for the launch
process and all its descendants after a short run: the sum of RSS (what ``ps`` shows, counting
shared pages once per process) and of PSS (shared pages split between the processes that share
them, the fairer total). If ``skydeck launch`` does not come up, the same processes are started
one by one instead (``skydeck core`` + ``skydeck run ...``) and the result says so.
"""

from __future__ import annotations

import contextlib
import sys
import time
from pathlib import Path
from typing import Any

import httpx

from benchmarks.processes import BenchError, Worker, worker_env
from services.runtime.ports import free_port_block

__all__ = ["measure_startup", "tree_memory_mb"]

NODES = ("sim", "perception", "control", "ai")
_TIMEOUT_S = 60.0
_RUN_BEFORE_MEMORY_S = 2.0


def _children() -> dict[int, list[int]]:
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        with contextlib.suppress(OSError):
            ppid = int((entry / "stat").read_text().rpartition(")")[2].split()[1])
            children.setdefault(ppid, []).append(int(entry.name))
    return children


def _tree(root: int) -> list[int]:
    children = _children()
    found, todo = [], [root]
    while todo:
        pid = todo.pop()
        found.append(pid)
        todo.extend(children.get(pid, []))
    return found


def tree_memory_mb(roots: list[int]) -> dict[str, float]:
    """RSS and PSS sums (MiB) of ``roots`` and all their descendants, and the process count."""
    rss_kb = pss_kb = 0
    pids = [pid for root in roots for pid in _tree(root)]
    for pid in pids:
        with contextlib.suppress(OSError):
            for line in Path(f"/proc/{pid}/smaps_rollup").read_text().splitlines():
                key, _, value = line.partition(":")
                if key == "Rss":
                    rss_kb += int(value.split()[0])
                elif key == "Pss":
                    pss_kb += int(value.split()[0])
    return {"rss_mb": rss_kb / 1024, "pss_mb": pss_kb / 1024, "processes": len(pids)}


def _all_ready(client: httpx.Client, base_port: int) -> bool:
    try:
        graph = client.get(f"http://127.0.0.1:{base_port}/api/graph").json()
        registered = {node["name"].lstrip("/") for node in graph["nodes"]}
        if not registered.issuperset(NODES):
            return False
        return all(
            client.get(f"http://127.0.0.1:{base_port + offset}/health").status_code == 200
            for offset in range(1, len(NODES) + 1)
        )
    except (httpx.HTTPError, ValueError, KeyError):
        return False


def _wait_ready(client: httpx.Client, base_port: int, workers: list[Worker], started: float) -> float:
    while time.monotonic() - started < _TIMEOUT_S:
        for worker in workers:
            if worker.returncode is not None:
                raise BenchError(f"{worker.name} exited ({worker.returncode}):\n{worker.tail(15)}")
        if _all_ready(client, base_port):
            return time.monotonic() - started
        time.sleep(0.01)
    raise BenchError(f"the workshop system was not ready within {_TIMEOUT_S:g} s")


def _base_port() -> int:
    return free_port_block(len(NODES) + 1)  # the core and each node


def measure_startup(*, seed: int = 1, fallback_only: bool = False) -> dict[str, Any]:
    """Start the workshop system, time it to every node ready, read its memory, stop it."""
    base = _base_port()
    env = worker_env(f"http://127.0.0.1:{base}")
    env.pop("SKYDECK_LOG_LEVEL", None)
    with httpx.Client(timeout=1.0) as client:
        if not fallback_only:
            argv = [sys.executable, "-m", "services.cli", "launch", "--base-port", str(base), "--seed", str(seed),
                    "--rosbridge-port", "0", "--foxglove-port", "0"]
            started = time.monotonic()
            launcher = Worker("launch", argv=argv, env=env)
            try:
                ready_s = _wait_ready(client, base, [launcher], started)
                time.sleep(_RUN_BEFORE_MEMORY_S)
                memory = tree_memory_mb([launcher.pid])
                stop_started = time.monotonic()
                launcher.stop(timeout_s=15.0)
                return {"how": "skydeck launch", "ready_s": ready_s, "stop_s": time.monotonic() - stop_started, **memory}
            except BenchError as error:
                launch_error = str(error).splitlines()[0]
            finally:
                launcher.stop()
        else:
            launch_error = "not tried"
        return {**_manual_startup(client, base, env, seed), "launch_error": launch_error}


def _manual_startup(client: httpx.Client, base: int, env: dict[str, str], seed: int) -> dict[str, Any]:
    cli = [sys.executable, "-m", "services.cli"]
    commands = [("core", [*cli, "core", "--port", str(base), "--rosbridge-port", "0", "--foxglove-port", "0"])]
    for offset, name in enumerate(NODES, start=1):
        extra = ["--seed", str(seed)] if name == "sim" else []
        commands.append((name, [*cli, "run", name, "--port", str(base + offset), *extra]))
    started = time.monotonic()
    workers = [Worker(f"manual-{name}", argv=argv, env=env) for name, argv in commands]
    try:
        ready_s = _wait_ready(client, base, workers, started)
        time.sleep(_RUN_BEFORE_MEMORY_S)
        memory = tree_memory_mb([w.pid for w in workers])
    finally:
        stop_started = time.monotonic()
        for worker in reversed(workers):
            worker.stop()
    return {"how": "skydeck core + skydeck run (launch unusable)", "ready_s": ready_s,
            "stop_s": time.monotonic() - stop_started, **memory}  # fmt: skip

