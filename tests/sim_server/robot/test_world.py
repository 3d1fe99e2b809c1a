"""The robot world's physics, measured: motors and contact move the robot, the watchdog stops it,
the laser reads the true geometry, the bumper and odometry report what happened."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

import pytest

from sim_server.drone.commands import InvalidCommand
from sim_server.robot.limits import (
    CMD_VEL_TIMEOUT_S,
    LEG_RADIUS_M,
    LEG_SPACING_M,
    MAX_ANGULAR_SPEED,
    MAX_LINEAR_SPEED,
    MAX_ROBOTS,
    NO_RETURN,
    PERSON_SPEED,
    PHYSICS_HZ,
    RANGE_MAX_M,
    ROBOT_RADIUS_M,
    ROBOT_STARTS_M,
    ROOM_HALF_SIZE_M,
    SCAN_ANGLE_INCREMENT,
    SCAN_BEAMS,
)
from sim_server.robot.world import RobotWorld, RobotWorldConfig, bumper_part

COMMAND_EVERY_STEPS = PHYSICS_HZ // 30  # a 30 Hz command stream


@pytest.fixture
def make_world() -> Iterator[Callable[..., RobotWorld]]:
    worlds: list[RobotWorld] = []

    def make(**config: int) -> RobotWorld:
        world = RobotWorld(RobotWorldConfig(seed=config.pop("seed", 1), **config))
        worlds.append(world)
        return world

    yield make
    for world in worlds:
        world.close()


@pytest.fixture
def room(make_world: Callable[..., RobotWorld]) -> RobotWorld:
    """One robot in a room without obstacles."""
    return make_world(obstacles=0)


def drive(world: RobotWorld, v: float, w: float, seconds: float, robot: int = 0) -> None:
    """Stream a command at 30 Hz for ``seconds`` of sim time."""
    for _ in range(round(seconds * PHYSICS_HZ / COMMAND_EVERY_STEPS)):
        world.set_cmd_vel(robot, v, w)
        world.step(COMMAND_EVERY_STEPS)


def test_the_robot_starts_at_the_origin_facing_x_and_stands_still(room: RobotWorld) -> None:
    assert room.robot_pose(0) == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    room.step(60 * PHYSICS_HZ)  # a minute with no command: the motors hold the wheels
    x, y, yaw = room.robot_pose(0)
    assert math.hypot(x, y) < 1e-3 and abs(yaw) < 1e-3
    assert room.robot_tilt_deg(0) < 1.0


@pytest.mark.parametrize(
    ("v", "w", "expected_v", "expected_w"),
    [(0.2, 0.0, 0.2, 0.0), (1.0, 0.0, MAX_LINEAR_SPEED, 0.0), (-0.1, 0.0, -0.1, 0.0),
     (0.0, 1.0, 0.0, 1.0), (0.0, -9.0, 0.0, -MAX_ANGULAR_SPEED), (0.15, 0.5, 0.15, 0.5)],
)  # fmt: skip
def test_it_drives_at_the_command_within_its_limits(
    room: RobotWorld, v: float, w: float, expected_v: float, expected_w: float
) -> None:
    assert room.set_cmd_vel(0, v, w) == (expected_v, expected_w)  # the command as clamped
    drive(room, v, w, 0.5)  # accelerate
    x0, y0, yaw0 = room.robot_pose(0)
    turned = 0.0
    travelled = 0.0
    for _ in range(30):  # 1 s, measured in 30 slices
        drive(room, v, w, 1 / 30)
        x1, y1, yaw1 = room.robot_pose(0)
        travelled += math.copysign(math.hypot(x1 - x0, y1 - y0), expected_v or 1.0)
        turned += math.remainder(yaw1 - yaw0, math.tau)
        x0, y0, yaw0 = x1, y1, yaw1
    assert travelled == pytest.approx(expected_v, abs=0.01)
    assert turned == pytest.approx(expected_w, abs=0.03)
    assert room.robot_tilt_deg(0) < 2.0


def test_the_watchdog_stops_the_robot_half_a_second_after_the_last_command(room: RobotWorld) -> None:
    drive(room, 0.3, 0.0, 1.0)
    room.step(round((CMD_VEL_TIMEOUT_S - 0.05) * PHYSICS_HZ))
    assert room.command(0) == (0.3, 0.0)
    room.step(round(0.1 * PHYSICS_HZ))
    assert room.command(0) == (0.0, 0.0)
    room.step(round(0.5 * PHYSICS_HZ))  # braking
    x_stopped = room.robot_pose(0)[0]
    room.step(2 * PHYSICS_HZ)
    assert room.robot_velocity(0)[0] == pytest.approx(0.0, abs=1e-3)
    assert room.robot_pose(0)[0] == pytest.approx(x_stopped, abs=1e-3)
    assert 0.35 < x_stopped < 0.55  # 1 s at 0.3 m/s, 0.5 s more, then a short stop


def test_a_command_that_is_not_finite_is_refused_and_changes_nothing(room: RobotWorld) -> None:
    drive(room, 0.2, 0.0, 0.5)
    for bad in (math.nan, math.inf, "fast"):
        with pytest.raises(InvalidCommand, match="cmd_vel: linear.x="):
            room.set_cmd_vel(0, bad, 0.0)
    assert room.command(0) == (0.2, 0.0)  # the last good command, until the watchdog ends it
    room.step(2 * PHYSICS_HZ)
    assert room.robot_velocity(0)[0] == pytest.approx(0.0, abs=1e-3)
    with pytest.raises(IndexError):
        room.set_cmd_vel(1, 0.1, 0.0)  # there is one robot


def _legs(world: RobotWorld) -> list[tuple[float, float]]:
    """Where the centres of the person's two legs are (x, y)."""
    px, py, heading = world.person_pose()
    half = LEG_SPACING_M / 2.0
    return [(px - s * half * math.sin(heading), py + s * half * math.cos(heading)) for s in (1, -1)]


def _expected_ranges(world: RobotWorld) -> list[float]:
    """Each beam's true distance to the walls and the person's legs, by plain geometry."""
    x, y, yaw = world.robot_pose(0)
    legs = _legs(world)
    ranges = []
    for i in range(SCAN_BEAMS):
        a = yaw + i * SCAN_ANGLE_INCREMENT
        dx, dy = math.cos(a), math.sin(a)
        best = math.inf
        for d, p in ((dx, x), (dy, y)):  # the walls
            if abs(d) > 1e-12:
                best = min(best, (math.copysign(ROOM_HALF_SIZE_M, d) - p) / d)
        for lx, ly in legs:  # ray against a circle
            ox, oy = x - lx, y - ly
            b = ox * dx + oy * dy
            disc = b * b - (ox * ox + oy * oy - LEG_RADIUS_M**2)
            if disc >= 0 and -b - math.sqrt(disc) > 0:
                best = min(best, -b - math.sqrt(disc))
        ranges.append(best if best <= RANGE_MAX_M else NO_RETURN)
    return ranges


def test_the_scan_reads_the_true_distances_counter_clockwise_from_ahead(room: RobotWorld) -> None:
    ranges = room.scan(0)
    assert len(ranges) == SCAN_BEAMS
    assert ranges[0] == pytest.approx(ROOM_HALF_SIZE_M, abs=0.01)  # the +x wall, straight ahead
    assert ranges[180] == pytest.approx(ROOM_HALF_SIZE_M, abs=0.01)
    assert ranges[270] == pytest.approx(ROOM_HALF_SIZE_M, abs=0.01)  # -y: on the right
    assert ranges[45] == NO_RETURN  # the corner is 5.7 m away, beyond range_max
    # Somewhere else, turned, with the person walking by: every beam against plain geometry.
    drive(room, 0.3, 0.0, 3.0)
    drive(room, 0.2, 0.9, 2.0)
    room.step(PHYSICS_HZ)  # stopped (the watchdog), the person has walked on
    ranges = room.scan(0)
    expected = _expected_ranges(room)
    seen_legs = 0
    for i, (got, want) in enumerate(zip(ranges, expected, strict=True)):
        if want == NO_RETURN:
            assert got == NO_RETURN, f"beam {i}"
        else:
            assert got == pytest.approx(want, abs=0.01), f"beam {i}"
        seen_legs += want != NO_RETURN and got < 0.999 * min(_wall_distances(room, i))
    assert seen_legs > 0, "the person's legs should be in view from here"


def _wall_distances(world: RobotWorld, beam: int) -> list[float]:
    x, y, yaw = world.robot_pose(0)
    a = yaw + beam * SCAN_ANGLE_INCREMENT
    d = (math.cos(a), math.sin(a))
    return [(math.copysign(ROOM_HALF_SIZE_M, c) - p) / c for c, p in zip(d, (x, y), strict=True) if abs(c) > 1e-12]


def test_the_robot_stops_at_a_wall_and_its_front_bumper_says_so(room: RobotWorld) -> None:
    assert not room.bump(0)
    drive(room, 0.3, 0.0, 16.0)  # 4.8 m of driving towards a wall 4 m away
    x, _, _ = room.robot_pose(0)
    assert x == pytest.approx(ROOM_HALF_SIZE_M - ROBOT_RADIUS_M, abs=0.005)  # against it, not in it
    bump = room.bump(0)
    assert (bump.left_front or bump.right_front) and not (bump.left_side or bump.right_side)
    assert room.robot_tilt_deg(0) < 2.0
    assert room.odometry(0).x > x + 0.002  # the wheels slipped as it pushed: odometry drifted
    drive(room, -0.2, 0.0, 1.0)  # backing off releases the bumper
    assert not room.bump(0)


@pytest.mark.parametrize(
    ("bearing", "part"),
    [(0.0, "left_front"), (-1.0, "right_front"), (44.0, "left_front"), (60.0, "left_side"),
     (-100.0, "right_side"), (150.0, None), (-179.0, None), (400.0, "left_front")],
)  # fmt: skip
def test_the_bumper_part_by_bearing(bearing: float, part: str | None) -> None:
    assert bumper_part(bearing) == part


def test_the_person_walks_the_loop_and_pushes_nothing_through(room: RobotWorld) -> None:
    x0, y0, _ = room.person_pose()
    room.step(4 * PHYSICS_HZ)
    x1, y1, heading = room.person_pose()
    assert math.hypot(x1 - x0, y1 - y0) / 4 == pytest.approx(PERSON_SPEED, rel=0.1)
    assert room.loop.distance_to(x1, y1) < 0.05  # on the loop
    room.step(round(room.loop.length_m / PERSON_SPEED * PHYSICS_HZ))  # once round
    x2, y2, _ = room.person_pose()
    assert math.hypot(x2 - x1, y2 - y1) < 0.1


def test_a_robot_in_the_persons_way_is_shoved_never_walked_through(room: RobotWorld) -> None:
    drive(room, 0.0, math.pi / 4, 2.0)  # a quarter turn: facing +y
    drive(room, 0.3, 0.0, 4.8)  # onto the loop's lower side (y = 1.44 at x = 0)
    x0, y0, _ = room.robot_pose(0)
    assert room.loop.distance_to(x0, y0) < 0.1, (x0, y0)
    closest = math.inf
    for _ in range(round(room.loop.length_m / PERSON_SPEED * PHYSICS_HZ / COMMAND_EVERY_STEPS)):  # once round
        room.step(COMMAND_EVERY_STEPS)
        x, y, _ = room.robot_pose(0)
        closest = min(closest, *(math.hypot(lx - x, ly - y) for lx, ly in _legs(room)))
    assert closest > ROBOT_RADIUS_M + LEG_RADIUS_M - 0.02, "a leg went into the robot"
    x, y, _ = room.robot_pose(0)
    assert math.hypot(x - x0, y - y0) > 0.1, "the person walked by without touching the robot"


def test_a_robot_driven_into_another_stops_against_it_with_its_bumper_pressed(
    make_world: Callable[..., RobotWorld],
) -> None:
    world = make_world(robots=3, obstacles=0)
    assert ROBOT_STARTS_M[2] == (-1.5, 0.0) and ROBOT_STARTS_M[0] == (0.0, 0.0)  # robot 2 faces robot 0
    drive(world, 0.3, 0.0, 8.0, robot=2)  # 2.4 m of driving at a robot 1.5 m ahead
    x2, y2, _ = world.robot_pose(2)
    x0, y0, _ = world.robot_pose(0)
    assert x2 < x0 and math.hypot(x0 - x2, y0 - y2) > 2 * ROBOT_RADIUS_M - 0.01, "one robot went into the other"
    bump = world.bump(2)
    assert bump.left_front or bump.right_front


def test_odometry_tracks_the_truth_while_driving_a_square(room: RobotWorld) -> None:
    corners = []
    for _ in range(4):
        drive(room, 0.3, 0.0, 3.0)
        corners.append(room.robot_pose(0)[:2])
        drive(room, 0.0, math.pi / 4, 2.0)
    room.step(PHYSICS_HZ)
    assert corners[1] == pytest.approx((0.9, 0.9), abs=0.1)  # it did drive a square
    x, y, yaw = room.robot_pose(0)
    odometry = room.odometry(0)
    # It drifts a little, as real odometry does (docs/robot.md gives the figures).
    assert math.hypot(odometry.x - x, odometry.y - y) < 0.01
    assert abs(math.remainder(odometry.yaw - yaw, math.tau)) < math.radians(0.3)


def test_several_robots_each_follow_their_own_commands(make_world: Callable[..., RobotWorld]) -> None:
    world = make_world(robots=MAX_ROBOTS)
    for i, start in enumerate(ROBOT_STARTS_M):
        assert world.robot_pose(i)[:2] == pytest.approx(start, abs=1e-6)
    drive(world, 0.3, 0.0, 2.0, robot=1)
    assert world.robot_pose(1)[0] == pytest.approx(ROBOT_STARTS_M[1][0] + 0.55, abs=0.05)
    for other in (0, 2, 3):
        assert world.robot_pose(other)[:2] == pytest.approx(ROBOT_STARTS_M[other], abs=1e-3)


def test_reset_puts_robots_and_person_back_in_the_same_room(make_world: Callable[..., RobotWorld]) -> None:
    world = make_world(seed=5, robots=2)
    obstacles = list(world.obstacles)
    person = world.person_pose()
    drive(world, 0.3, 0.5, 2.0)
    world.reset()
    assert world.robot_pose(0) == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    assert world.person_pose() == pytest.approx(person, abs=1e-6)
    assert world.obstacles == obstacles
    odometry = world.odometry(0)
    assert (odometry.x, odometry.y, odometry.yaw) == (0.0, 0.0, 0.0)
    assert world.command(0) == (0.0, 0.0)


def test_the_same_seed_builds_the_same_room(make_world: Callable[..., RobotWorld]) -> None:
    assert make_world(seed=3).obstacles == make_world(seed=3).obstacles
    assert make_world(seed=3).obstacles != make_world(seed=4).obstacles


@pytest.mark.parametrize(("config", "message"), [({"robots": 0}, "robots=0"), ({"robots": 5}, "robots=5"),
                                                 ({"obstacles": -1}, "obstacles=-1"), ({"obstacles": 99}, "obstacles=99")])  # fmt: skip
def test_bad_configs_are_refused(config: dict[str, int], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        RobotWorldConfig(**config)


def test_a_closed_world_says_so(make_world: Callable[..., RobotWorld]) -> None:
    world = make_world()
    world.close()
    world.close()  # idempotent
    with pytest.raises(RuntimeError, match="closed"):
        world.step()
