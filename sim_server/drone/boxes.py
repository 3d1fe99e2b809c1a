"""Where the boxes appear: random, repeatable, apart from each other and from the drone.

Pure sampling with a caller-owned :class:`random.Random`, so a seed fixes the whole sequence of
box sets across resets.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from sim_server.drone.limits import (
    ARENA_HALF_SIZE_M,
    BOX_MIN_START_DISTANCE_M,
    BOX_SIZE_M,
    BOX_SPAWN_Z_M,
    BOX_TUMBLE_ALLOWANCE_M,
    START_XY_M,
)

__all__ = ["BoxSpawn", "sample_boxes"]

BOX_MIN_SEPARATION_M = 2.0 * math.sqrt(3.0) * BOX_SIZE_M / 2.0 + 0.5
"""Least horizontal distance between two box centres at spawn: more than two half-diagonals
(the boxes cannot touch in any orientation, even stacked in height) plus room to tip over."""

_MAX_TRIES_PER_BOX = 1000


@dataclass(frozen=True, slots=True)
class BoxSpawn:
    """Initial pose of one box: centre (x, y, z) and orientation quaternion (x, y, z, w)."""

    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]


def sample_boxes(rng: random.Random, count: int) -> list[BoxSpawn]:
    """Draw ``count`` non-overlapping box poses in the arena, away from the drone's start.

    Centres are uniform in the arena square at BOX_SPAWN_Z_M heights, rejecting (and drawing
    again) any too close to the start or to a box already placed.

    Raises ValueError when the boxes cannot be placed (far more than the arena holds).
    """
    placed: list[BoxSpawn] = []
    sx, sy = START_XY_M
    clearance = BOX_MIN_START_DISTANCE_M + BOX_TUMBLE_ALLOWANCE_M
    for _ in range(count):
        for _try in range(_MAX_TRIES_PER_BOX):
            x = rng.uniform(-ARENA_HALF_SIZE_M, ARENA_HALF_SIZE_M)
            y = rng.uniform(-ARENA_HALF_SIZE_M, ARENA_HALF_SIZE_M)
            z = rng.uniform(*BOX_SPAWN_Z_M)
            orientation = random_quaternion(rng)
            if math.hypot(x - sx, y - sy) <= clearance:
                continue
            if all(
                math.hypot(x - b.position[0], y - b.position[1]) > BOX_MIN_SEPARATION_M
                for b in placed
            ):
                placed.append(BoxSpawn((x, y, z), orientation))
                break
        else:
            raise ValueError(f"cannot place {count} boxes apart in the arena; use fewer boxes")
    return placed


def random_quaternion(rng: random.Random) -> tuple[float, float, float, float]:
    """A rotation drawn uniformly from SO(3) (Shoemake's method), as (x, y, z, w)."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1.0 - u1), math.sqrt(u1)
    return (
        a * math.sin(math.tau * u2),
        a * math.cos(math.tau * u2),
        b * math.sin(math.tau * u3),
        b * math.cos(math.tau * u3),
    )
