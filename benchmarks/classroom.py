"""A class on one machine (issue 35): thirty students' robots in one room, and thirty dashboards
and the instructor's class page on one core.

A class's core (``--class-tokens``, thirty students) and the robot world with a robot per
student (``SKYDECK_SIM_STUDENTS``), each with the class's process token, as ``skydeck class``
starts them; then one of two loads (:mod:`benchmarks.classroom_worker`):

- ``world``: the world at real time while the students' programs read every robot's scan,
  odometry and bumper: whether it keeps its pace (sim seconds per wall second, from ``/clock``),
  each reader's delivered rate, and the world's CPU (a fraction of one core);
- ``world_max``: the same at ``--speed max``: the real-time factor, and sim seconds per second
  of the world's CPU time (what one core of its own would give: the figure a loaded machine
  changes least);
- ``dashboards``: the world at real time while thirty students' dashboards read their robot
  through the core with their tokens and the instructor's class page reads every robot's truth
  and polls ``GET /api/class``: each reader's delivered rate against what it asked for (or what
  the world published, if its pace gave less), and the world's pace meanwhile.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path
from typing import Any

import httpx

from benchmarks.classroom_worker import CLASS_VIEW_HZ, DASHBOARD_RATES_HZ
from benchmarks.processes import BenchError, Worker, free_port, start_core, wait_http, worker_env
from benchmarks.sim import sim_argv
from services.access import make_class_tokens, write_tokens

__all__ = ["measure_class"]

_PROCESS_TOKEN = "the-bench-class-processes-token"
_SIM_RATES_HZ = {"scan": 5.0, "odom": 30.0, "bump": 30.0}  # per sim second: sim_server/robot/limits.py
_TRUTH_HZ = 10.0  # /simulator/robots
_SETTLE_S = 2.0


def _sim_time_s(client: httpx.Client, url: str) -> tuple[float, float]:
    stamp = client.get(f"{url}/clock").json()
    return stamp["sec"] + stamp["nanosec"] * 1e-9, time.monotonic()


def measure_class(load: str, *, students: int, window_s: float) -> dict[str, Any]:
    """One reading of ``load`` (``world`` or ``dashboards``, see the module docstring)."""
    names = [f"s{i + 1:02d}" for i in range(students)]
    with tempfile.TemporaryDirectory() as folder:
        tokens_file = Path(folder) / "class-tokens.csv"
        write_tokens(tokens_file, make_class_tokens(names))
        core, url = start_core(
            "class-core", flags=("--class-tokens", str(tokens_file)), env=worker_env(SKYDECK_TOKEN=_PROCESS_TOKEN)
        )
        try:
            return _measure(load, url, names, tokens_file, core, window_s)
        finally:
            core.stop()


def _measure(load: str, url: str, names: list[str], tokens_file: Path, core: Worker, window_s: float) -> dict[str, Any]:
    env = worker_env(url, SKYDECK_TOKEN=_PROCESS_TOKEN, SKYDECK_SIM_STUDENTS=",".join(names))
    port = free_port()
    speed = "max" if load == "world_max" else "1"
    argv = sim_argv(port, seed=1, world_args=["--world", "robot", "--obstacles", "0"])
    argv[argv.index("--speed") + 1] = speed
    sim_url = f"http://127.0.0.1:{port}"
    headers = {"Authorization": f"Bearer {_PROCESS_TOKEN}"}
    with Worker("class-sim", argv=argv, env=env) as sim, httpx.Client(timeout=5.0, headers=headers) as client:
        wait_http(f"{sim_url}/health", 120.0, what="the class's world", worker=sim)
        wait_http(f"{sim_url}/clock", 60.0, what="the class's /clock", worker=sim)
        if load != "dashboards":
            readers = Worker("class-nodes", "benchmarks.classroom_worker", "nodes", "--students", ",".join(names), env=env)
        else:
            readers = Worker(
                "class-dashboards", "benchmarks.classroom_worker", "dashboards", "--core", url, "--tokens", str(tokens_file),
                env=env,
            )  # fmt: skip
        with readers:
            readers.expect("READY", 120.0)
            time.sleep(_SETTLE_S)
            sim_cpu, core_cpu = sim.cpu_seconds(), core.cpu_seconds()
            sim0, wall0 = _sim_time_s(client, sim_url)
            time.sleep(window_s)
            sim1, wall1 = _sim_time_s(client, sim_url)
            wall = wall1 - wall0
            sim_cpu_s = sim.cpu_seconds() - sim_cpu
            sim_cpu, core_cpu = sim_cpu_s / wall, (core.cpu_seconds() - core_cpu) / wall
            readers.send("stop")
            result = readers.expect("RESULT", 30.0)
    rates = result["rates"]
    if not any(rate for group in rates.values() for rate in group):
        raise BenchError(f"the class's {load} readers received nothing")
    reading: dict[str, Any] = {
        "rtf": (sim1 - sim0) / wall, "rtf_per_cpu": (sim1 - sim0) / max(sim_cpu_s, 1e-3),
        "sim_cpu": sim_cpu, "core_cpu": core_cpu,
    }  # fmt: skip
    if load == "world_max":
        return reading  # as fast as it goes: readers take what they can, delivery is not the question
    # The world's topics come at their sim-time rates times its pace; a reader gets those, or
    # the rate it asked for if that is lower (the world's pace is the other rows' question).
    published = {kind: hz * reading["rtf"] for kind, hz in _SIM_RATES_HZ.items()}
    if load == "world":
        expected = published
    else:
        expected = {kind: min(hz, published[kind]) for kind, hz in DASHBOARD_RATES_HZ.items()}
        truth_hz = min(CLASS_VIEW_HZ, _TRUTH_HZ * reading["rtf"])
        reading["class_view_delivery"] = result["class_view_rate"] / truth_hz
        reading["class_page_p50_ms"] = result["class_page_p50_ms"]
        reading["class_page_max_ms"] = result["class_page_max_ms"]
        reading["closed"] = result["closed"]
    reading["delivery"] = {kind: min(group) / expected[kind] for kind, group in rates.items()}
    reading["min_delivery"] = min(reading["delivery"].values())
    return reading
