"""The criteria library on made-up runs: each figure measured where it is known, pass and fail."""

from __future__ import annotations

import math

import pytest

from services.grading.criteria import CRITERIA
from services.grading.shapes import Box, Pose
from tests.services.grading.tracks import along, bump, polyline, room, run


def measure(name: str, tracks, **params):  # type: ignore[no-untyped-def]
    spec = CRITERIA[name]
    return spec.run(tracks, spec.params.model_validate(params))


SQUARE = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)]


def test_a_square_driven_well_has_small_corner_errors_and_closes() -> None:
    tracks = run(along(polyline(SQUARE, 0.2), 25.0))
    assert measure("drive_square.corner_error_m", tracks).value < 1e-6
    assert measure("drive_square.closure_m", tracks).value < 1e-6


def test_a_square_turned_the_wrong_way_misses_its_corners() -> None:
    right = [(x, -y) for x, y in SQUARE]
    tracks = run(along(polyline(right, 0.2), 25.0))
    figure = measure("drive_square.corner_error_m", tracks)
    assert figure.value == pytest.approx(1.0)  # corners 2 and 3 are a side away from the path
    assert figure.detail.startswith("corner 2")
    assert measure("drive_square.corner_error_m", tracks, turn="right").value < 1e-6


def test_a_square_cut_short_does_not_close() -> None:
    tracks = run(along(polyline(SQUARE[:4], 0.2), 20.0))
    assert measure("drive_square.closure_m", tracks).value == pytest.approx(1.0)


def test_estop_figures_of_a_robot_that_stops_before_the_wall() -> None:
    robot = along(polyline([(0.0, 0.0), (3.5, 0.0)], 0.2), 25.0)
    tracks = run(robot)
    assert measure("estop.travel_m", tracks).value == pytest.approx(3.5)
    assert measure("estop.clearance_m", tracks).value == pytest.approx(0.5 - 0.165)
    assert measure("estop.moved_after_stop_m", tracks).value == pytest.approx(0.0)
    assert measure("estop.bumps", tracks).value == 0.0


def test_estop_a_robot_that_creeps_on_after_stopping_moved() -> None:
    stop_then_creep = along(polyline([(0.0, 0.0), (3.0, 0.0)], 0.2), 20.0)
    creep = [Pose(20.0 + i / 10, 3.0 + 0.01 * i, 0.0) for i in range(1, 31)]  # 0.1 m/s for 3 s
    figure = measure("estop.moved_after_stop_m", run(stop_then_creep + creep))
    assert figure.value == pytest.approx(0.3)
    never = along(polyline([(0.0, 0.0), (3.9, 0.0)], 0.2), 19.0)  # still driving at the end
    assert measure("estop.moved_after_stop_m", run(never)).value == math.inf


def test_bumps_count_contacts_not_messages() -> None:
    held = [bump(5.0 + i / 30) for i in range(30)]  # one second pressed: one contact
    again = [bump(9.0), bump(9.04)]
    tracks = run(along(polyline([(0.0, 0.0), (1.0, 0.0)], 0.2), 10.0), bumps=held + again)
    figure = measure("wall_follower.bumps", tracks)
    assert figure.value == 2.0
    assert [mark.kind for mark in figure.marks] == ["bump", "bump"]


def test_a_robot_following_the_wall_on_its_right_stays_in_the_band() -> None:
    # From the middle to 0.5 m off the +y wall, then along it heading -x (the wall on its right).
    path = polyline([(0.0, 0.0), (0.0, 3.5), (-3.0, 3.5)], 0.2)
    tracks = run(along(path, 40.0))
    options = {"distance": 0.5, "tolerance": 0.15, "side": "right"}
    # Driving at the wall it is ahead, not on the right: in the band once it turned along it.
    assert measure("wall_follower.time_to_wall_s", tracks, **options).value == pytest.approx(3.5 / 0.2, abs=0.15)
    assert measure("wall_follower.band_fraction", tracks, **options).value > 0.95
    assert measure("wall_follower.followed_m", tracks, **options).value == pytest.approx(3.0, abs=0.2)
    # The same path seen with the wall on the left: never in the band once it turned.
    assert measure("wall_follower.band_fraction", tracks, distance=0.5, tolerance=0.15, side="left").value < 0.1


def test_a_robot_driving_into_the_wall_leaves_the_band() -> None:
    path = polyline([(0.0, 0.0), (0.0, 3.5), (0.0, 3.85)], 0.2)  # on into the wall
    tracks = run(along(path, 40.0))
    options = {"distance": 0.5, "tolerance": 0.15, "side": "either"}
    assert measure("wall_follower.band_fraction", tracks, **options).value < 0.2
    assert measure("wall_follower.followed_m", tracks, **options).value < 0.5


@pytest.mark.parametrize("drift_m", [-0.3, 0.3])
def test_a_wall_ahead_is_on_no_side_whichever_way_the_robot_drifts(drift_m: float) -> None:
    # At the +y wall, a little askew: the wall is ahead (bearing ~ 5 degrees), never beside it.
    tracks = run(along(polyline([(0.0, 0.0), (drift_m, 3.8)], 0.2), 25.0))
    for side in ("right", "left", "either"):
        assert measure("wall_follower.time_to_wall_s", tracks, side=side).value == math.inf


def test_a_robot_that_never_reaches_a_wall() -> None:
    tracks = run(along(polyline([(0.0, 0.0), (1.0, 0.0)], 0.2), 20.0))
    assert measure("wall_follower.time_to_wall_s", tracks).value == math.inf
    assert measure("wall_follower.band_fraction", tracks).value == 0.0


def test_person_gap_band() -> None:
    person = along(lambda t: (-2.0 + 0.25 * t, 2.0), 40.0)
    close = along(lambda t: (-2.8 + 0.25 * t, 2.0), 40.0)  # 0.8 m behind
    far = along(lambda t: (-4.0 + 0.25 * t, 2.0), 40.0)  # 2 m behind
    assert measure("person_follower.gap_band_fraction", run(close, people=person)).value == 1.0
    assert measure("person_follower.gap_band_fraction", run(far, people=person)).value == 0.0
    # Only after the warm-up: catching up from far is not held against the robot.
    catching = [Pose(p.t, (f.x if p.t < 8 else c.x), 2.0) for p, f, c in zip(person, far, close, strict=True)]
    assert measure("person_follower.gap_band_fraction", run(catching, people=person), warmup_s=10).value == 1.0


def facing_x(robot: list[Pose]) -> list[Pose]:
    """The robot starts facing +x (the goal is in the frame it starts in)."""
    return [Pose(robot[0].t, robot[0].x, robot[0].y, 0.0), *robot[1:]]


def test_obstacle_avoider_goal_and_progress() -> None:
    reached = run(facing_x(along(polyline([(0.0, 0.0), (1.0, 2.0), (3.5, 2.5)], 0.2), 40.0)))
    assert measure("obstacle_avoider.goal_error_m", reached, goal_x=3.5, goal_y=2.5).value == pytest.approx(0.0, abs=1e-9)
    assert measure("obstacle_avoider.progress", reached, goal_x=3.5, goal_y=2.5).value == pytest.approx(1.0)
    stuck = run(facing_x(along(polyline([(0.0, 0.0), (1.0, 0.0)], 0.2), 40.0)))
    figure = measure("obstacle_avoider.progress", stuck, goal_x=2.0, goal_y=0.0)
    assert figure.value == pytest.approx(0.5)


def test_fsm_switch_and_the_wall_after_it() -> None:
    path = polyline([(0.0, 0.0), (3.5, 0.0), (3.5, 3.0)], 0.2)  # to the +x wall, then along it (on the right)
    states = [(0.0, "drive_square"), (17.0, "follow_wall")]
    tracks = run(along(path, 35.0), states=states)
    assert measure("fsm.switched", tracks).value == 1.0
    assert measure("fsm.switch_clearance_m", tracks).value == pytest.approx(0.6 - 0.165, abs=0.02)
    assert measure("fsm.wall_band_fraction", tracks).value > 0.9
    assert measure("fsm.switched", run(along(path, 35.0), states=[(0.0, "drive_square")])).value == 0.0


def drone_run(path: list[tuple[float, float]], boxes: list[tuple[float, float]]):  # type: ignore[no-untyped-def]
    flown = [Pose(p.t, p.x, p.y, 0.0, 3.0) for p in along(polyline(path, 5.0), 30.0)]
    return run([], drone=flown, boxes=[Box(x, y, 2.0, 2.0, 0.0, "box") for x, y in boxes], world="drone")


def test_drone_visits_and_path_against_the_best_tour() -> None:
    boxes = [(5.0, 0.0), (10.0, 0.0)]
    best = drone_run([(0.0, 0.0), (10.0, 0.0)], boxes)
    assert measure("drone_mission.boxes_visited", best).value == 1.0
    # Flown until over the last box (within the visit radius of its centre): a little under the tour.
    assert measure("drone_mission.path_ratio", best).value == pytest.approx(9.5 / 10.0)
    # The far box first: 10 m, then 5.83 m back to the near one (less the visit radius), against
    # the near one first: 5.83 m and 5.83 m.
    detour = drone_run([(0.0, 0.0), (10.0, 0.0), (5.0, 3.0)], [(10.0, 0.0), (5.0, 3.0)])
    leg = math.hypot(5.0, 3.0)
    ratio = measure("drone_mission.path_ratio", detour).value  # samples 0.5 m apart: within one
    assert ratio == pytest.approx((10.0 + leg - 0.5) / (2 * leg), abs=0.5 / (2 * leg))
    missed = drone_run([(0.0, 0.0), (5.0, 0.0)], boxes)
    assert measure("drone_mission.boxes_visited", missed).value == 0.5
    assert measure("drone_mission.path_ratio", missed).value == math.inf


def test_a_run_without_what_a_criterion_reads_is_not_measured() -> None:
    empty = run([], obstacles=room())
    figure = measure("wall_follower.band_fraction", empty)
    assert math.isnan(figure.value)
    assert "no robot pose" in figure.detail
