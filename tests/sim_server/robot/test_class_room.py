"""A class's room (issue 35): one robot per student, named, on a grid clear of the person's walk."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest
from pydantic import ValidationError

from sim_server.robot.layout import PersonLoop, class_starts
from sim_server.robot.limits import (
    CLASS_PERSON_CLEARANCE_M,
    MAX_CLASS_ROBOTS,
    ROBOT_RADIUS_M,
    ROOM_HALF_SIZE_M,
)
from sim_server.robot.settings import RobotSettings
from sim_server.robot.world import RobotWorld, RobotWorldConfig
from sim_server.worlds import world_options


def _closest(starts: list[tuple[float, float]]) -> float:
    return min(math.hypot(a[0] - b[0], a[1] - b[1]) for i, a in enumerate(starts) for b in starts[i + 1 :])


@pytest.mark.parametrize("count", [2, 5, 12, 30, MAX_CLASS_ROBOTS])
def test_a_class_starts_apart_inside_the_room_and_off_the_persons_walk(count: int) -> None:
    loop = PersonLoop()
    starts = class_starts(count, loop)
    assert len(starts) == len(set(starts)) == count
    assert _closest(starts) >= 0.8  # four robot radii and more: no two touch, each can turn
    for x, y in starts:
        assert max(abs(x), abs(y)) <= ROOM_HALF_SIZE_M - 0.4
        assert loop.distance_to(x, y) >= CLASS_PERSON_CLEARANCE_M


def test_a_small_class_spreads_over_the_room() -> None:
    assert _closest(class_starts(2, PersonLoop())) > 4.0
    assert _closest(class_starts(30, PersonLoop())) > 1.0


def test_more_students_than_the_room_holds_are_refused() -> None:
    with pytest.raises(ValueError, match="do not fit"):
        class_starts(200, PersonLoop())
    with pytest.raises(ValueError, match="more than a room holds"):
        RobotWorldConfig(students=tuple(f"s{i}" for i in range(MAX_CLASS_ROBOTS + 1)))


@pytest.fixture
def class_world() -> Iterator[RobotWorld]:
    world = RobotWorld(RobotWorldConfig(seed=3, obstacles=2, students=tuple(f"s{i}" for i in range(12))))
    yield world
    world.close()


def test_a_class_world_has_a_robot_per_student_standing_still_where_it_started(class_world: RobotWorld) -> None:
    assert class_world.robot_count == 12
    class_world.step(class_world.PHYSICS_HZ)  # a second: nothing pushes anyone
    for index, (sx, sy) in enumerate(class_world.starts):
        x, y, _ = class_world.robot_pose(index)
        assert math.hypot(x - sx, y - sy) < 0.01
        for box in class_world.obstacles:  # the boxes keep clear of every start
            assert math.hypot(box.x - sx, box.y - sy) > box.radius + ROBOT_RADIUS_M


def test_a_class_robot_drives_on_its_own_command(class_world: RobotWorld) -> None:
    class_world.set_cmd_vel(5, 0.0, 1.5)
    class_world.step(class_world.PHYSICS_HZ // 2)
    assert abs(class_world.robot_pose(5)[2]) > 0.3
    assert all(abs(class_world.robot_pose(i)[2]) < 0.01 for i in range(12) if i != 5)


def test_the_students_setting_is_checked_and_is_no_launch_option() -> None:
    assert RobotSettings(students=" alice, bob ").student_names == ("alice", "bob")
    assert RobotSettings().student_names == ()
    for bad, said in (("alice,alice", "named twice"), ("alice,9lives", "cannot name a namespace")):
        with pytest.raises(ValidationError, match=said):
            RobotSettings(students=bad)
    assert "students" not in world_options()
