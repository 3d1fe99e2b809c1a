"""The room's layout: seeded obstacles that keep their distances, and the person's loop."""

from __future__ import annotations

import math
import random

import pytest

from sim_server.robot.layout import PersonLoop, place_obstacles
from sim_server.robot.limits import (
    CORRIDOR_HALF_WIDTH_M,
    LEG_RADIUS_M,
    LEG_SPACING_M,
    MAX_OBSTACLES,
    OBSTACLE_GAP_M,
    OBSTACLE_SIZE_M,
    PERSON_LOOP_CENTRE_M,
    PERSON_LOOP_RADII_M,
    ROBOT_RADIUS_M,
    ROBOT_STARTS_M,
    ROOM_HALF_SIZE_M,
    WALL_LANE_M,
)

LOOP = PersonLoop()


def _corners(o):  # the four corners of a turned square box
    h = o.size / 2.0
    c, s = math.cos(o.yaw), math.sin(o.yaw)
    return [(o.x + c * dx - s * dy, o.y + s * dx + c * dy) for dx in (-h, h) for dy in (-h, h)]


@pytest.mark.parametrize("seed", range(60))
def test_obstacles_keep_their_distances(seed: int) -> None:
    obstacles = place_obstacles(random.Random(seed), MAX_OBSTACLES, LOOP)
    assert len(obstacles) == MAX_OBSTACLES
    for i, o in enumerate(obstacles):
        assert OBSTACLE_SIZE_M[0] <= o.size <= OBSTACLE_SIZE_M[1]
        corners = _corners(o)
        # A lane along every wall, and the corridor from robot 1's start to the +x wall.
        assert all(max(abs(x), abs(y)) <= ROOM_HALF_SIZE_M - WALL_LANE_M + 1e-9 for x, y in corners)
        assert not any(x > -ROBOT_RADIUS_M and abs(y) < CORRIDOR_HALF_WIDTH_M for x, y in corners)
        for sx, sy in ROBOT_STARTS_M:
            assert math.hypot(o.x - sx, o.y - sy) >= o.radius + ROBOT_RADIUS_M + OBSTACLE_GAP_M
        legs = LEG_SPACING_M / 2.0 + LEG_RADIUS_M
        assert LOOP.distance_to(o.x, o.y) >= o.radius + legs + OBSTACLE_GAP_M
        for other in obstacles[i + 1 :]:
            assert math.hypot(o.x - other.x, o.y - other.y) >= o.radius + other.radius + OBSTACLE_GAP_M


def test_the_same_seed_builds_the_same_room() -> None:
    assert place_obstacles(random.Random(7), 4, LOOP) == place_obstacles(random.Random(7), 4, LOOP)
    assert place_obstacles(random.Random(7), 4, LOOP) != place_obstacles(random.Random(8), 4, LOOP)


def test_more_obstacles_than_the_room_holds_are_refused() -> None:
    with pytest.raises(ValueError, match="cannot place 200 obstacles"):
        place_obstacles(random.Random(1), 200, LOOP)


def test_the_person_walks_the_ellipse_counter_clockwise() -> None:
    (cx, cy), (a, b) = PERSON_LOOP_CENTRE_M, PERSON_LOOP_RADII_M
    expected = math.pi * (3 * (a + b) - math.sqrt((3 * a + b) * (a + 3 * b)))  # Ramanujan
    assert LOOP.length_m == pytest.approx(expected, rel=1e-4)
    x, y, heading = LOOP.at(0.0)
    assert (x, y) == pytest.approx((cx + a, cy)) and heading == pytest.approx(math.pi / 2, abs=0.02)
    x, y, heading = LOOP.at(LOOP.length_m / 4)  # a quarter of the way: the top, walking -x
    assert (x, y) == pytest.approx((cx, cy + b), abs=0.01)
    assert abs(heading) == pytest.approx(math.pi, abs=0.01)
    assert LOOP.at(LOOP.length_m + 1.0) == pytest.approx(LOOP.at(1.0))  # round and round
    for s in (0.3, 5.0, 9.9):
        px, py, _ = LOOP.at(s)
        assert ((px - cx) / a) ** 2 + ((py - cy) / b) ** 2 == pytest.approx(1.0, abs=1e-3)


def test_the_persons_path_keeps_out_of_the_corridor_and_off_the_starts() -> None:
    legs = LEG_SPACING_M / 2.0 + LEG_RADIUS_M
    assert min(y for _, y in LOOP.points) - legs > CORRIDOR_HALF_WIDTH_M
    for sx, sy in ROBOT_STARTS_M:
        assert LOOP.distance_to(sx, sy) > legs + ROBOT_RADIUS_M + OBSTACLE_GAP_M
    assert all(max(abs(x), abs(y)) + legs < ROOM_HALF_SIZE_M for x, y in LOOP.points)
