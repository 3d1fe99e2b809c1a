"""Simulator speed: the real-time factor of the simulator node at ``--speed max`` against a bare
PyBullet loop of the same scene (1 drone + N boxes; or the robot world's room with its laser).

The node is the real one (``skydeck run sim --speed max``, ``--world robot`` for the robot
world), registered with a core and publishing at its stated rates (drone: pose and clock 60 Hz
of sim time, boxes 10 Hz, state 5 Hz; robot: odom, bump, tf and clock 30 Hz, scan 5 Hz, truth
10 Hz). RTF = sim-time advance / wall time, read from the node's ``/clock`` (GET, the latest
message) at both ends of a window after the world has settled: once with nobody subscribed,
once with a subscriber node reading ``/drone/pose`` (drone) or ``/scan`` (robot); and, with
the subscriber, per second of the simulator process's CPU time (/proc), which a loaded machine
changes far less than the wall-clock figure (not at all only in theory: caches and cores are
shared too; docs/performance.md has runs at load 5-7). The references
are :func:`sim_server.drone.speed.measure`'s bare ``stepSimulation`` loop and
:func:`sim_server.robot.speed.measure`'s bare loop casting the same rays, each in its own process.
"""

from __future__ import annotations

import sys
import time
from typing import Any

import httpx

from benchmarks.processes import BenchError, Worker, free_port, wait_http, worker_env
from benchmarks.topics import CoreHolder
from sim_server.drone.limits import PHYSICS_HZ
from sim_server.robot.limits import PHYSICS_HZ as ROBOT_PHYSICS_HZ

__all__ = ["measure_bare", "measure_node", "measure_robot_bare", "sim_argv"]

# What the subscriber reads in each world: (topic, type).
_WATCHED = {
    "drone": ("/drone/pose", "geometry_msgs/msg/PoseStamped"),
    "robot": ("/scan", "sensor_msgs/msg/LaserScan"),
}

_SETTLE_S = 0.5  # wall seconds: at tens of times real time the boxes have long landed


def measure_bare(*, boxes: int, steps: int, seed: int = 1) -> dict[str, float]:
    """RTF of the bare PyBullet loop and of the world without the node, in a worker process."""
    with Worker("sim-bare", "benchmarks.sim_worker", "--boxes", str(boxes), "--steps", str(steps), "--seed", str(seed)) as worker:
        reading = worker.expect("RESULT", 120.0)
    return {
        "bare_rtf": reading["bare_steps_per_s"] / PHYSICS_HZ,
        "world_rtf": reading["world_steps_per_s"] / PHYSICS_HZ,
    }


def sim_argv(port: int, *, seed: int, boxes: int = 8, world_args: list[str] | None = None) -> list[str]:
    """``skydeck run sim`` at speed max on ``port``, quiet (the drone world of ``boxes`` boxes
    unless ``world_args`` say otherwise)."""
    return [
        sys.executable, "-m", "services.cli", "run", "sim", "--port", str(port), "--log-level", "warning",
        "--speed", "max", "--seed", str(seed), *(world_args or ["--boxes", str(boxes)]),
    ]  # fmt: skip


def measure_robot_bare(*, steps: int, seed: int = 1) -> dict[str, float]:
    """RTF of the robot world's bare loop (with the same rays) and of the world without the
    node, and each one's milliseconds per scan, in a worker process."""
    with Worker("robot-bare", "benchmarks.robot_worker", "--steps", str(steps), "--seed", str(seed)) as worker:
        reading = worker.expect("RESULT", 120.0)
    return {
        "bare_rtf": reading["bare_steps_per_s"] / ROBOT_PHYSICS_HZ,
        "world_rtf": reading["world_steps_per_s"] / ROBOT_PHYSICS_HZ,
        "scan_ms": reading["scan_ms"],
        "bare_scan_ms": reading["bare_scan_ms"],
        "bare_rtf_cpu": reading["bare_steps_per_cpu_s"] / ROBOT_PHYSICS_HZ,
    }


def measure_node(
    core: CoreHolder, *, boxes: int = 8, window_s: float, subscriber: bool = True, seed: int = 1, world: str = "drone"
) -> dict[str, Any]:
    """RTF of the simulator node at speed max, without and (optionally) with a subscriber of its
    main stream (the drone's pose, the robot's scan)."""
    env = worker_env(core.get())
    port = free_port()
    argv = sim_argv(port, seed=seed, world_args=["--boxes", str(boxes)] if world == "drone" else ["--world", world])
    url = f"http://127.0.0.1:{port}"
    with Worker("sim-node", argv=argv, env=env) as sim, httpx.Client(timeout=5.0) as client:
        wait_http(f"{url}/health", 60.0, what="simulator node", worker=sim)
        wait_http(f"{url}/clock", 30.0, what="simulator /clock", worker=sim)
        time.sleep(_SETTLE_S)
        result: dict[str, Any] = {"rtf_alone": _rtf(client, url, window_s, sim)[0]}
        if subscriber:
            topic, type_name = _WATCHED[world]
            with Worker(
                "sim-sub", "benchmarks.topic_skydeck", "sub", "--topic", topic, "--type", type_name, "--warmup", "0", env=env
            ) as sub:
                sub.expect("READY", 30.0)
                time.sleep(_SETTLE_S)  # the link is up within a fraction of a second
                result["rtf_subscribed"], result["rtf_subscribed_cpu"] = _rtf(client, url, window_s, sim)
                sub.send("stop")
                received = sub.expect("RESULT", 10.0)
            if received["received"] == 0:
                raise BenchError(f"the {topic} subscriber received nothing from the simulator")
            result["stream_rate"] = received["rate"]
    return result


def _sim_time_s(client: httpx.Client, url: str) -> tuple[float, float]:
    wall = time.monotonic()
    stamp = client.get(f"{url}/clock").json()
    return stamp["sec"] + stamp["nanosec"] * 1e-9, wall


def _rtf(client: httpx.Client, url: str, window_s: float, sim: Worker) -> tuple[float, float]:
    """Sim seconds per wall second, and per second of the simulator process's CPU time."""
    cpu0 = sim.cpu_seconds()
    sim0, wall0 = _sim_time_s(client, url)
    time.sleep(window_s)
    sim1, wall1 = _sim_time_s(client, url)
    cpu1 = sim.cpu_seconds()
    return (sim1 - sim0) / (wall1 - wall0), (sim1 - sim0) / max(cpu1 - cpu0, 1e-3)
