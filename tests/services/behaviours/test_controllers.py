"""The behaviours' logic without processes: scans made by plain geometry, poses given."""

from __future__ import annotations

import math

import pytest

from services.behaviours.drive_square import SquareDriver
from services.behaviours.laser import clusters, fit_wall, nearest_in_sector, points
from services.behaviours.obstacle_avoider import GoalSeeker, clear_headings
from services.behaviours.person_follower import PersonFollower, find_people
from services.behaviours.robot import Pose2D
from services.behaviours.wall_follower import WallFollower
from services.runtime.parameters import InvalidParameterValueException
from shared_models.sensor_msgs import LaserScan

BEAMS = 360
STEP = math.tau / BEAMS


def scan_of(*shapes: tuple[str, tuple[float, ...]], max_range: float = 5.0) -> LaserScan:
    """A scan from the origin facing +x, of lines ("line", (a, b, c): ax + by = c) and circles
    ("circle", (x, y, r)); 0.0 where nothing is within range."""
    ranges = []
    for i in range(BEAMS):
        dx, dy = math.cos(i * STEP), math.sin(i * STEP)
        best = math.inf
        for kind, p in shapes:
            if kind == "line":
                a, b, c = p
                denominator = a * dx + b * dy
                if abs(denominator) > 1e-12 and c / denominator > 0:
                    best = min(best, c / denominator)
            else:
                cx, cy, r = p
                along = cx * dx + cy * dy
                disc = along**2 - (cx**2 + cy**2 - r**2)
                if disc >= 0 and along - math.sqrt(disc) > 0:
                    best = min(best, along - math.sqrt(disc))
        ranges.append(best if best <= max_range else 0.0)
    return LaserScan(angle_min=0.0, angle_max=(BEAMS - 1) * STEP, angle_increment=STEP, range_min=0.2, range_max=max_range, ranges=ranges)


def legs(x: float, y: float) -> list[tuple[str, tuple[float, ...]]]:
    return [("circle", (x, y + 0.15, 0.1)), ("circle", (x, y - 0.15, 0.1))]


# -- laser ---------------------------------------------------------------------------------


def test_nearest_in_a_sector_skips_no_returns() -> None:
    scan = scan_of(("line", (1.0, 0.0, 2.0)))  # a wall 2 m ahead, nothing behind
    assert nearest_in_sector(scan, 0.0, 10.0) == pytest.approx(2.0, abs=1e-9)
    assert nearest_in_sector(scan, 180.0, 30.0) == math.inf
    # From 40 to 50 degrees, the nearest return is at the sector's edge nearest to ahead.
    assert 2.0 / math.cos(math.radians(40)) <= nearest_in_sector(scan, 45.0, 5.0) <= 2.0 / math.cos(math.radians(41))


def test_a_wall_is_fitted_with_its_distance_and_angle() -> None:
    tilted = math.radians(10)  # a wall on the right, turned 10 degrees counter-clockwise
    scan = scan_of(("line", (-math.sin(tilted), math.cos(tilted), -0.7)))
    wall = fit_wall(points(scan, -90.0, 40.0))
    assert wall is not None
    assert wall.distance == pytest.approx(0.7, abs=1e-6) and wall.angle == pytest.approx(tilted, abs=1e-6)
    assert fit_wall([(1.0, 1.0)] * 4) is None


def test_clusters_split_on_gaps_and_join_across_the_scans_ends() -> None:
    scan = scan_of(*legs(1.5, 0.0), ("line", (0.0, 1.0, 2.0)), max_range=2.5)
    found = clusters(scan)
    small = [c for c in found if c.width < 0.25]
    assert len(small) == 2  # the two legs ahead, across beam 0 (the scan's two ends)
    left, right = sorted(small, key=lambda c: c.y)
    assert -0.25 < left.y < -0.05 and 0.05 < right.y < 0.25 and left.x == pytest.approx(right.x, abs=0.01)
    assert any(c.width > 1.0 for c in found)  # the wall


def test_people_are_pairs_of_legs_and_a_box_is_not_a_leg() -> None:
    scan = scan_of(*legs(2.0, 1.0), ("circle", (1.0, -1.0, 0.1)))
    (person,) = find_people(scan, lone_legs=False)
    assert person == pytest.approx((2.0 - 0.07, 1.0), abs=0.05)  # the legs' visible fronts
    assert len(find_people(scan)) == 2  # with the lone leg
    wide = scan_of(("circle", (1.5, 0.0, 0.3)))  # something 60 cm across
    assert find_people(wide) == []


# -- controllers ----------------------------------------------------------------------------


def test_the_square_is_four_legs_and_four_left_turns_by_odometry() -> None:
    square = SquareDriver(side=1.0, speed=0.2, turn_rate=0.6)
    x = y = yaw = 0.0
    dt = 0.05
    corners = []
    for _ in range(4000):
        v, w = square.update(Pose2D(x, y, yaw))
        if square.done:
            break
        if v == 0.0 and w == 0.0:
            corners.append((round(x, 2), round(y, 2)))
        x += v * math.cos(yaw) * dt
        y += v * math.sin(yaw) * dt
        yaw = math.remainder(yaw + w * dt, math.tau)
    assert square.done and square.legs_done == 4
    assert math.hypot(x, y) < 0.03
    assert (1.0, 0.0) in corners and (1.0, 1.0) in corners and (0.0, 1.0) in corners
    assert square.update(Pose2D(x, y, yaw)) == (0.0, 0.0)


def test_the_wall_follower_steers_to_its_distance_and_turns_at_a_corner() -> None:
    follower = WallFollower("right", distance=0.5, speed=0.2)
    far = scan_of(("line", (0.0, 1.0, -0.8)))  # a wall on the right, 0.8 m away, parallel
    v, w = follower.update(far)
    assert follower.state == "following" and v > 0 and w < 0  # towards it
    near = scan_of(("line", (0.0, 1.0, -0.3)))
    assert follower.update(near)[1] > 0  # away from it
    corner = scan_of(("line", (0.0, 1.0, -0.5)), ("line", (1.0, 0.0, 0.5)))
    assert follower.update(corner) == (0.0, pytest.approx(1.0)) and follower.state == "turning"
    assert WallFollower("left").update(scan_of(("line", (0.0, 1.0, 0.8))))[1] > 0
    with pytest.raises(InvalidParameterValueException, match="side must be 'left' or 'right'"):
        WallFollower("up")


def test_the_person_follower_takes_a_walking_person_and_keeps_its_distance() -> None:
    follower = PersonFollower(distance=0.8, speed=0.3)
    here = Pose2D(0.0, 0.0, 0.0)
    standing = scan_of(*legs(2.0, 0.5))
    assert follower.update(standing, here, 0.0) == (0.0, pytest.approx(0.6))  # nobody walked yet
    assert follower.update(scan_of(*legs(2.0, 0.5)), here, 0.2)[0] == 0.0  # still nobody: legs stay put
    v, w = follower.update(scan_of(*legs(2.05, 0.5)), here, 0.4)  # they moved: a person
    assert follower.state == "following" and v > 0 and w > 0
    close = PersonFollower(distance=0.8, speed=0.3)
    close.update(scan_of(*legs(0.6, 0.0)), here, 0.0)
    assert close.update(scan_of(*legs(0.65, 0.0)), here, 0.2)[0] < 0.0  # too near: it backs away
    # Legs whose near sides the laser sees 0.8 m away: at its distance, it holds still.
    assert close.update(scan_of(*legs(0.88, 0.0)), here, 0.4)[0] == pytest.approx(0.0, abs=0.02)
    v, w = close.update(scan_of(), here, 2.0)  # gone: it stops and turns where they were
    assert v == 0.0 and abs(w) == pytest.approx(0.6)
    assert close.state == "lost"


def test_the_avoider_takes_the_clear_heading_nearest_the_goal() -> None:
    box = scan_of(("circle", (1.0, 0.0, 0.3)))  # something round in the way, straight ahead
    found = points(box)
    clear = clear_headings(found, lane_half_width=0.3, lookahead=1.5)
    assert 0.0 not in clear and math.radians(90) in clear
    seeker = GoalSeeker((3.0, 0.0))
    v, w = seeker.update(box, Pose2D(0.0, 0.0, 0.0))
    assert seeker.state == "avoiding" and w != 0.0
    assert GoalSeeker((3.0, 0.0)).update(scan_of(), Pose2D(2.95, 0.0, 0.0)) == (0.0, 0.0)
