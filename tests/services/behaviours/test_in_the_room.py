"""Each behaviour, run as a user runs it (`skydeck run NAME --use-sim-time`) against the robot
world (core and simulator in subprocesses, 8x real time), its outcome measured in the world
from the simulator's truth (/simulator/robots, /simulator/people, /bump), never assumed.

The tests share one simulator and reset it first; every wait is on a message or a log line.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

from sim_server.robot.limits import ROBOT_RADIUS_M, ROOM_HALF_SIZE_M
from tests.sim_server.robot.room import (
    Recorder,
    behaviour,
    latest,
    reset_room,
    stamp_s,
    start_room,
    truth,
    wait_for,
    yaw_of,
)
from tests.web_ui.system import System

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(300)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "1", "--speed", "8")
    yield system
    system.stop()


@pytest.fixture
def fresh(room: System) -> System:
    """The room with its robot back at the start and the person at the start of the walk."""
    return reset_room(room)


def _xy(pose: dict) -> tuple[float, float]:
    return pose["position"]["x"], pose["position"]["y"]


def _track(recorder: Recorder) -> list[tuple[float, float, float, float]]:
    """(sim time, x, y, yaw) of robot 1 from recorded /simulator/robots."""
    return [(stamp_s(m), *_xy(m["poses"][0]), yaw_of(m["poses"][0]["orientation"])) for m in recorder.messages]


def _to_wall(x: float, y: float) -> float:
    return ROOM_HALF_SIZE_M - max(abs(x), abs(y))


def _pressed(bump: dict) -> bool:
    return bool(bump["left_front"] or bump["left_side"] or bump["right_front"] or bump["right_side"])


def test_drive_square_closes_within_20_cm_of_its_start(fresh: System) -> None:
    with Recorder(fresh, "/simulator/robots") as robots, behaviour(fresh, "drive_square") as node:
        node.wait_for_line("square done", 180)
        wait_for(fresh, "/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3)
    x, y, _ = truth(fresh)
    assert math.hypot(x, y) < 0.2
    track = _track(robots)
    for corner in ((1.0, 0.0), (1.0, 1.0), (0.0, 1.0)):  # it went round a 1 m square
        assert min(math.hypot(cx - corner[0], cy - corner[1]) for _, cx, cy, _ in track) < 0.15, corner


def test_estop_stops_short_of_the_wall_without_touching_it(fresh: System) -> None:
    with Recorder(fresh, "/bump") as bumps, behaviour(fresh, "estop", "--ros-args", "-p", "distance:=0.5") as node:
        node.wait_for_line("the way ahead is clear: driving", 180)
        node.wait_for_line("ahead: stopped", 180)
        stopped = wait_for(fresh, "/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3)
        wait_for(fresh, "/clock", lambda m: m["sec"] + m["nanosec"] * 1e-9 > stamp_s(stopped) + 1.0)
        x, y, _ = truth(fresh)
    assert bumps.messages and not any(_pressed(b) for b in bumps.messages)
    gap = ROOM_HALF_SIZE_M - x - ROBOT_RADIUS_M  # between the bumper and the +x wall
    assert 0.15 < gap < 0.5 and abs(y) < 0.1


def test_wall_follower_holds_its_distance_within_15_cm_for_a_minute(fresh: System) -> None:
    with Recorder(fresh, "/simulator/robots") as robots, behaviour(fresh, "wall_follower") as node:
        node.wait_for_line("following", 180)
        start = stamp_s(latest(fresh, "/simulator/robots"))
        wait_for(fresh, "/simulator/robots", lambda m: stamp_s(m) > start + 80.0, timeout_s=180)
    track = _track(robots)
    # From the first moment it is at its distance, a whole minute of sim time.
    settled = next(t for t, x, y, _ in track if abs(_to_wall(x, y) - 0.5) < 0.05)
    minute = [(t, x, y) for t, x, y, _ in track if settled <= t <= settled + 60.0]
    assert minute[-1][0] - minute[0][0] > 59.0
    worst = max(abs(_to_wall(x, y) - 0.5) for _, x, y in minute)
    assert worst <= 0.15, worst
    assert math.dist(minute[0][1:], minute[-1][1:]) > 3.0  # it went along the walls, round a corner


def test_person_follower_stays_within_its_band_of_the_walking_person(fresh: System) -> None:
    distance = 0.8
    with (
        Recorder(fresh, "/simulator/robots") as robots,
        Recorder(fresh, "/simulator/people") as people,
        behaviour(fresh, "person_follower", "--ros-args", "-p", f"distance:={distance}") as node,
    ):
        node.wait_for_line("following", 180)
        start = stamp_s(latest(fresh, "/simulator/robots"))
        wait_for(fresh, "/simulator/robots", lambda m: stamp_s(m) > start + 60.0, timeout_s=180)
    person_at = {stamp_s(m): _xy(m["poses"][0]) for m in people.messages}
    gaps = [(t, math.dist((x, y), person_at[t])) for t, x, y, _ in _track(robots) if t in person_at]
    caught_up = next(t for t, gap in gaps if gap < distance + 0.3)
    following = [gap for t, gap in gaps if caught_up <= t <= caught_up + 40.0]
    assert len(following) > 300  # 40 s of sim time at 10 Hz
    assert distance - 0.4 <= min(following) and max(following) <= distance + 0.5, (min(following), max(following))
    walked = [person_at[t] for t in sorted(person_at)]
    assert math.dist(walked[0], walked[-1]) > 1.0 or len(walked) > 300  # the person did walk


def test_obstacle_avoider_reaches_a_goal_behind_an_obstacle_without_a_bump(fresh: System) -> None:
    boxes = [m for m in latest(fresh, "/simulator/obstacles")["markers"] if m["ns"] == "obstacles"]
    box = min(boxes, key=lambda m: math.hypot(*_xy(m["pose"])))  # the nearest, and a goal behind it
    bx, by = _xy(box["pose"])
    reach = box["scale"]["x"] / math.sqrt(2) + 0.6
    goal = (bx + reach * bx / math.hypot(bx, by), by + reach * by / math.hypot(bx, by))
    args = ("--ros-args", "-p", f"goal_x:={goal[0]:.3f}", "-p", f"goal_y:={goal[1]:.3f}")
    with (
        Recorder(fresh, "/bump") as bumps,
        Recorder(fresh, "/simulator/robots") as robots,
        behaviour(fresh, "obstacle_avoider", *args) as node,
    ):
        node.wait_for_line("reached", 180)
        wait_for(fresh, "/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3)
    x, y, _ = truth(fresh)
    assert math.dist((x, y), goal) < 0.2
    assert bumps.messages and not any(_pressed(b) for b in bumps.messages)
    # It went round the box: the straight line from the start to the goal runs through it.
    track = _track(robots)
    assert min(math.dist((tx, ty), (bx, by)) for _, tx, ty, _ in track) > ROBOT_RADIUS_M + box["scale"]["x"] / 2


def test_fsm_drives_squares_until_the_wall_is_near_then_follows_it(fresh: System) -> None:
    with (
        Recorder(fresh, "/fsm/state") as states,
        Recorder(fresh, "/simulator/robots") as robots,
        behaviour(fresh, "fsm", "--ros-args", "-p", "side:=5.0") as node,
    ):
        node.wait_for_line("state follow_wall", 180)
        switched = stamp_s(latest(fresh, "/simulator/robots"))
        wait_for(fresh, "/simulator/robots", lambda m: stamp_s(m) > switched + 30.0, timeout_s=120)
    assert [s["data"] for s in states.messages][:2] == ["drive_square", "follow_wall"]
    later = [(x, y) for t, x, y, _ in _track(robots) if switched + 10.0 <= t]
    assert later and max(abs(_to_wall(x, y) - 0.5) for x, y in later) <= 0.15
