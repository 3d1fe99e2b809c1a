"""Mission quality: the AI's whole flight, take-off to touchdown, against the optimum for its
landing policy (``beside_last_box``: the best open tour plus the least clear distance beside its
last box; ``home``: the best closed tour).

Two measures:

- **planned** (:func:`measure_tours`, 20 seeded worlds, both policies): the flight the AI plans
  (:func:`services.ai.planner.plan_tour` with the policy's finishing legs, from the drone's start)
  against the optimum found by brute force over every order (8! = 40,320). Each world is the
  simulator's own ``World``, stepped until the boxes have landed. The nearest-first tour (the
  workshop's bonus) is reported alongside for scale.
- **flown** (:func:`fly_missions`, a few seeded worlds, the default policy): the real system
  (``skydeck launch --exclude ai`` and ``skydeck run ai``, a fresh state folder), the drone's
  ground track read from ``/drone/pose`` (horizontal distance from take-off to touchdown)
  against the optimum over the boxes perception saw, and the mission's sim time.

Run as a worker (``python -m benchmarks.mission --worlds 20``) so that PyBullet, which
prints its build time on stdout when imported, stays out of the benchmark's own output.
"""

from __future__ import annotations

import argparse
import asyncio
import itertools
import json
import math
import os
import signal
import statistics
import sys
import tempfile
import time
from collections.abc import Sequence
from typing import Any

from benchmarks.processes import Worker
from benchmarks.sink import emit
from services.ai.landing import LANDING_POLICIES, LandingPolicy, finishing_legs
from services.ai.planner import plan_tour
from services.launch.background import BackgroundProcess
from sim_server.drone.limits import MAX_SPEED_XY, MAX_SPEED_Z, ON_GROUND_Z_M, PHYSICS_HZ, START_XY_M

__all__ = [
    "GroundTrack",
    "brute_force_length",
    "fly_missions",
    "flights_in_worker",
    "least_flight_s",
    "measure_tours",
    "nearest_first_length",
    "optimal_flight_m",
    "tours_in_worker",
]

Point2 = tuple[float, float]
_SETTLE_STEPS = 3 * PHYSICS_HZ
_FLIGHT_SPEED = "10"  # fast, and still close enough to real time for the flight to be faithful
_FLIGHT_TIMEOUT_S = 120.0
_FLIGHT_ALTITUDE_M = 3.0  # control's


def least_flight_s(optimal_m: float) -> float:
    """No mission can be quicker: the optimal track at top speed, climb and descent at top rate."""
    return optimal_m / MAX_SPEED_XY + 2.0 * _FLIGHT_ALTITUDE_M / MAX_SPEED_Z


def settled_boxes(seed: int, boxes: int) -> tuple[Point2, list[Point2]]:
    """The drone's start and the landed boxes' (x, y) of the world with ``seed``."""
    from sim_server.drone.world import World, WorldConfig

    with World(WorldConfig(seed=seed, boxes=boxes)) as world:
        world.step(_SETTLE_STEPS)
        (sx, sy, _), _ = world.drone_pose()
        return (sx, sy), [(x, y) for (x, y, _), _ in world.boxes_poses()]


def brute_force_length(start: Point2, points: Sequence[Point2], finish: Sequence[float] | None = None) -> float:
    """The shortest tour from ``start`` over ``points`` (plus ``finish[last]``), trying every order."""
    n = len(points)
    ends = list(finish) if finish is not None else [0.0] * n
    from_start = [math.dist(start, p) for p in points]
    between = [[math.dist(p, q) for q in points] for p in points]
    best = math.inf
    for order in itertools.permutations(range(n)):
        length = from_start[order[0]]
        for a, b in itertools.pairwise(order):
            length += between[a][b]
            if length >= best:
                break
        else:
            best = min(best, length + ends[order[-1]])
    return best if n else 0.0


def optimal_flight_m(start: Point2, boxes: Sequence[Point2], policy: LandingPolicy, *, home: Point2 = START_XY_M) -> float:
    """The shortest whole flight over ``boxes`` that lands as ``policy`` says (brute force)."""
    return brute_force_length(start, boxes, finishing_legs(policy, boxes, home=home))


def nearest_first_length(start: Point2, points: list[Point2]) -> float:
    """The tour that always flies to the nearest box not yet visited (the workshop's bonus)."""
    left = list(points)
    here, total = start, 0.0
    while left:
        nearest = min(left, key=lambda p: math.dist(here, p))
        total += math.dist(here, nearest)
        left.remove(nearest)
        here = nearest
    return total


class GroundTrack:
    """What the drone flew, from its ``/drone/pose`` messages (as JSON): the horizontal track
    and the sim time from take-off to touchdown, the closest approach to each box, where it is."""

    def __init__(self, boxes: Sequence[Point2]) -> None:
        self.boxes = list(boxes)
        self.closest = [math.inf] * len(self.boxes)
        self.track_m = 0.0  # of the flights that have touched down
        self.flight_s = 0.0
        self.missed = 0  # poses lost on the way (header.seq gaps): the track would cut corners
        self.position: tuple[float, float, float] | None = None
        self._take_off_s: float | None = None  # while airborne
        self._airborne_m = 0.0
        self._seq: int | None = None

    @property
    def landed(self) -> bool:
        """On the ground after a flight."""
        return self._take_off_s is None and self.flight_s > 0.0

    def add(self, pose: dict[str, Any]) -> None:
        header, position = pose["header"], pose["pose"]["position"]
        if self._seq is not None and header["seq"] > self._seq + 1:
            self.missed += header["seq"] - self._seq - 1
        self._seq = header["seq"]
        stamp_s = header["stamp"]["sec"] + header["stamp"]["nanosec"] * 1e-9
        here = (position["x"], position["y"], position["z"])
        for i, box in enumerate(self.boxes):
            self.closest[i] = min(self.closest[i], math.dist(here[:2], box))
        if self._take_off_s is not None and self.position is not None:
            self._airborne_m += math.dist(here[:2], self.position[:2])
        airborne = here[2] > ON_GROUND_Z_M
        if airborne and self._take_off_s is None:
            self._take_off_s, self._airborne_m = stamp_s, 0.0
        elif not airborne and self._take_off_s is not None:
            self.track_m += self._airborne_m
            self.flight_s += stamp_s - self._take_off_s
            self._take_off_s = None
        self.position = here


def measure_tours(*, worlds: int = 20, boxes: int = 8) -> dict[str, Any]:
    """Planned / optimal whole flight per landing policy, and nearest-first / optimal open tour,
    over ``worlds`` seeded worlds (seeds 0..)."""
    ratios: dict[str, list[float]] = {policy: [] for policy in LANDING_POLICIES}
    nearest, plan_ms = [], []
    for seed in range(worlds):
        start, points = settled_boxes(seed, boxes)
        for policy in LANDING_POLICIES:
            legs = finishing_legs(policy, points, home=START_XY_M)  # type: ignore[arg-type]
            began = time.perf_counter()
            tour = plan_tour(start, points, finish=legs)
            plan_ms.append((time.perf_counter() - began) * 1e3)
            ratios[policy].append(tour.length_m / brute_force_length(start, points, legs))
        nearest.append(nearest_first_length(start, points) / brute_force_length(start, points))
    result: dict[str, Any] = {
        "worlds": worlds,
        "nearest_first_mean_ratio": statistics.fmean(nearest),
        "nearest_first_worst_ratio": max(nearest),
        "plan_ms_median": statistics.median(plan_ms),
    }
    for policy, values in ratios.items():
        result[policy] = {
            "mean_ratio": statistics.fmean(values),
            "worst_ratio": max(values),
            "optimal_worlds": sum(1 for r in values if r <= 1 + 1e-9),
        }
    return result


# -- flown missions ---------------------------------------------------------------------------


async def _fly_one(seed: int, boxes: int, state_dir: str) -> dict[str, Any]:
    """One mission on the real system; the flown track, the optimum, the mission's sim time."""
    import httpx
    from websockets.asyncio.client import connect

    from services.runtime.edge.links import stream_url
    from services.runtime.ports import free_port_block

    base = free_port_block(5)
    core, sim = f"http://127.0.0.1:{base}", f"http://127.0.0.1:{base + 1}"
    env = {**os.environ, "SKYDECK_STATE_DIR": state_dir, "SKYDECK_LOG_LEVEL": "WARNING", "SKYDECK_CORE_URL": core}
    cli = [sys.executable, "-m", "services.cli"]
    launch = [*cli, "launch", "--base-port", str(base), "--speed", _FLIGHT_SPEED, "--seed", str(seed),
              "--boxes", str(boxes), "--exclude", "ai"]  # fmt: skip
    processes = [BackgroundProcess(launch, name="launch", env=env)]
    try:
        async with httpx.AsyncClient(timeout=2.0) as http, asyncio.timeout(_FLIGHT_TIMEOUT_S):
            polygon = await _latest(http, core + "/perception/boxes", lambda m: len(m["points"]) == boxes)
            track = GroundTrack([(p["x"], p["y"]) for p in polygon["points"]])
            async with connect(stream_url(sim, "/drone/pose", queue=10_000), max_size=None) as poses:
                # The AI starts only now, so the track is read from before its take-off.
                ai = [*cli, "run", "ai", "--port", str(base + 4), "--use-sim-time", "--start-mission"]
                processes.append(BackgroundProcess(ai, name="ai", env=env))
                reader = asyncio.create_task(_read_poses(poses, track))
                try:
                    status = await _latest(http, core + "/ai/status", lambda m: m["state"] in ("done", "error"))
                    while not track.landed and not reader.done():
                        await asyncio.sleep(0.05)  # the touchdown pose may trail the AI's status
                    if reader.done():
                        await reader  # the pose stream broke: say why
                finally:
                    reader.cancel()
    finally:
        for process in reversed(processes):
            await asyncio.to_thread(process.stop, signal.SIGINT, 20.0)
    optimum = optimal_flight_m(START_XY_M, track.boxes, "beside_last_box")
    return {
        "seed": seed,
        "state": status["state"],
        "visited": len(set(status["visited"])),
        "flown_m": track.track_m,
        "optimal_m": optimum,
        "ratio": track.track_m / optimum,
        "flight_s": track.flight_s,
        "least_flight_s": least_flight_s(optimum),
        "missed_poses": track.missed,
        "worst_visit_m": max(track.closest, default=0.0),
    }


async def _read_poses(poses: Any, track: GroundTrack) -> None:
    async for frame in poses:
        track.add(json.loads(frame))


async def _latest(http: Any, url: str, ready: Any) -> dict[str, Any]:
    """GET a topic's latest message until ``ready(message)``; the launch may still be starting."""
    import httpx

    while True:
        try:
            reply = await http.get(url)
            if reply.status_code == 200 and ready(message := reply.json()):
                return message  # type: ignore[no-any-return]
        except (httpx.HTTPError, ValueError):
            pass  # not up yet
        await asyncio.sleep(0.1)


def fly_missions(*, seeds: Sequence[int], boxes: int = 8) -> dict[str, Any]:
    """Fly one mission per seed; the flown / optimal ratios and mission times."""
    flights = []
    for seed in seeds:
        with tempfile.TemporaryDirectory(prefix="skydeck-bench-ai-") as state_dir:
            flights.append(asyncio.run(_fly_one(seed, boxes, state_dir)))
    ratios = [f["ratio"] for f in flights]
    return {
        "mean_ratio": statistics.fmean(ratios),
        "worst_ratio": max(ratios),
        "flight_s_median": statistics.median(f["flight_s"] for f in flights),
        "least_flight_s_median": statistics.median(f["least_flight_s"] for f in flights),
        "completed": sum(1 for f in flights if f["state"] == "done" and f["visited"] == boxes),
        "flights": flights,
    }


def tours_in_worker(*, worlds: int = 20, boxes: int = 8) -> dict[str, Any]:
    """:func:`measure_tours` in a worker process."""
    with Worker("mission", "benchmarks.mission", "--worlds", str(worlds), "--boxes", str(boxes)) as worker:
        return worker.expect("RESULT", 300.0)


def flights_in_worker(*, seeds: Sequence[int], boxes: int = 8) -> dict[str, Any]:
    """:func:`fly_missions` in a worker process."""
    seed_text = ",".join(str(seed) for seed in seeds)
    with Worker("flights", "benchmarks.mission", "--fly", seed_text, "--boxes", str(boxes)) as worker:
        return worker.expect("RESULT", _FLIGHT_TIMEOUT_S * (len(seeds) + 1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--worlds", type=int, default=20)
    parser.add_argument("--boxes", type=int, default=8)
    parser.add_argument("--fly", metavar="SEEDS", help="fly missions on these seeds (comma-separated) instead")
    args = parser.parse_args()
    if args.fly:
        emit("RESULT", fly_missions(seeds=[int(s) for s in args.fly.split(",")], boxes=args.boxes))
    else:
        emit("RESULT", measure_tours(worlds=args.worlds, boxes=args.boxes))


if __name__ == "__main__":
    main()
