"""Box spawning: in the arena, apart, away from the start, repeatable."""

from __future__ import annotations

import math
import random

import pytest

from sim_server.drone.boxes import BOX_MIN_SEPARATION_M, random_quaternion, sample_boxes
from sim_server.drone.limits import (
    ARENA_HALF_SIZE_M,
    BOX_MIN_START_DISTANCE_M,
    BOX_SIZE_M,
    BOX_SPAWN_Z_M,
    MAX_BOXES,
)


@pytest.mark.parametrize("seed", range(20))
def test_spawns_are_in_the_arena_apart_and_clear_of_the_start(seed: int) -> None:
    spawns = sample_boxes(random.Random(seed), 8)
    assert len(spawns) == 8
    for i, box in enumerate(spawns):
        x, y, z = box.position
        assert abs(x) <= ARENA_HALF_SIZE_M and abs(y) <= ARENA_HALF_SIZE_M
        assert BOX_SPAWN_Z_M[0] <= z <= BOX_SPAWN_Z_M[1]
        assert math.hypot(x, y) > BOX_MIN_START_DISTANCE_M
        assert math.fsum(c * c for c in box.orientation) == pytest.approx(1.0)
        for other in spawns[:i]:
            gap = math.dist(box.position[:2], other.position[:2])
            # farther apart than two half-diagonals: no overlap in any orientation
            assert gap > math.sqrt(3.0) * BOX_SIZE_M
            assert gap > BOX_MIN_SEPARATION_M


def test_same_rng_state_gives_same_boxes() -> None:
    assert sample_boxes(random.Random(7), 8) == sample_boxes(random.Random(7), 8)
    assert sample_boxes(random.Random(7), 8) != sample_boxes(random.Random(8), 8)


def test_the_largest_box_count_fits() -> None:
    assert len(sample_boxes(random.Random(0), MAX_BOXES)) == MAX_BOXES


def test_impossible_counts_are_refused() -> None:
    with pytest.raises(ValueError, match="fewer boxes"):
        sample_boxes(random.Random(0), 200)


def test_random_quaternions_cover_all_rotations() -> None:
    rng = random.Random(3)
    samples = [random_quaternion(rng) for _ in range(4000)]
    # uniform on SO(3): each component of the unit quaternion has mean 0 and mean square 1/4
    for axis in range(4):
        mean_square = sum(q[axis] ** 2 for q in samples) / len(samples)
        assert mean_square == pytest.approx(0.25, abs=0.02)
