"""Mission quality: the AI's planned tour against the optimal tour, over seeded worlds.

Each world is the simulator's own (``World(WorldConfig(seed=s, boxes=8))``), stepped until the
boxes have landed, so the points are where perception would see them. The AI plans with
:func:`services.ai.planner.plan_tour` from the drone's start; the optimum is found by brute
force over every order (8! = 40,320 for 8 boxes). Both are open tours, as the AI flies them.
The nearest-first tour (the workshop's bonus) is reported alongside for scale.

Run as a worker (``python -m services.bench.mission --worlds 20``) so that PyBullet, which
prints its build time on stdout when imported, stays out of the benchmark's own output.
"""

from __future__ import annotations

import argparse
import itertools
import math
import statistics
import time
from typing import Any

from services.ai.planner import plan_tour
from services.bench.processes import Worker
from services.bench.sink import emit
from sim_server.limits import PHYSICS_HZ

__all__ = ["brute_force_length", "measure_tours", "nearest_first_length", "tours_in_worker"]

Point2 = tuple[float, float]
_SETTLE_STEPS = 3 * PHYSICS_HZ


def settled_boxes(seed: int, boxes: int) -> tuple[Point2, list[Point2]]:
    """The drone's start and the landed boxes' (x, y) of the world with ``seed``."""
    from sim_server.world import World, WorldConfig

    with World(WorldConfig(seed=seed, boxes=boxes)) as world:
        world.step(_SETTLE_STEPS)
        (sx, sy, _), _ = world.drone_pose()
        return (sx, sy), [(x, y) for (x, y, _), _ in world.boxes_poses()]


def brute_force_length(start: Point2, points: list[Point2]) -> float:
    """The shortest open tour from ``start`` over ``points``, trying every order."""
    n = len(points)
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
            best = length
    return best if n else 0.0


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


def measure_tours(*, worlds: int = 20, boxes: int = 8) -> dict[str, Any]:
    """Planned / optimal and nearest-first / optimal over ``worlds`` seeded worlds (seeds 0..)."""
    ratios, nearest, plan_ms = [], [], []
    for seed in range(worlds):
        start, points = settled_boxes(seed, boxes)
        began = time.perf_counter()
        tour = plan_tour(start, points)
        plan_ms.append((time.perf_counter() - began) * 1e3)
        optimum = brute_force_length(start, points)
        ratios.append(tour.length_m / optimum)
        nearest.append(nearest_first_length(start, points) / optimum)
    return {
        "mean_ratio": statistics.fmean(ratios),
        "worst_ratio": max(ratios),
        "optimal_worlds": sum(1 for r in ratios if r <= 1 + 1e-9),
        "worlds": worlds,
        "nearest_first_mean_ratio": statistics.fmean(nearest),
        "nearest_first_worst_ratio": max(nearest),
        "plan_ms_median": statistics.median(plan_ms),
    }


def tours_in_worker(*, worlds: int = 20, boxes: int = 8) -> dict[str, Any]:
    """:func:`measure_tours` in a worker process."""
    with Worker("mission", "services.bench.mission", "--worlds", str(worlds), "--boxes", str(boxes)) as worker:
        return worker.expect("RESULT", 300.0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--worlds", type=int, default=20)
    parser.add_argument("--boxes", type=int, default=8)
    args = parser.parse_args()
    emit("RESULT", measure_tours(worlds=args.worlds, boxes=args.boxes))


if __name__ == "__main__":
    main()
