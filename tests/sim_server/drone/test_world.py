"""The world as a whole: boxes, determinism, reset, input checks, read-out."""

from __future__ import annotations

import math
from collections.abc import Callable

import pytest

from sim_server.drone.commands import ControlMode
from sim_server.drone.limits import (
    ARENA_HALF_SIZE_M,
    BOX_MIN_START_DISTANCE_M,
    BOX_SIZE_M,
    MAX_BOXES,
    ON_GROUND_Z_M,
    PHYSICS_DT_S,
    PHYSICS_HZ,
)
from sim_server.drone.world import InvalidCommand, Pose, World, WorldConfig
from tests.sim_server.drone.flight import stream_setpoint

MakeWorld = Callable[..., World]
TUMBLE_MARGIN_M = 2.0  # a box landing on a corner rolls up to ~1.7 m


def settle(world: World, seconds: float = 4.0) -> None:
    world.step(round(seconds * PHYSICS_HZ))


def test_boxes_fall_and_land_flat_in_the_arena_clear_of_the_start(make_world: MakeWorld) -> None:
    for seed in (1, 2, 3):
        world = make_world(seed=seed, boxes=8)
        assert all(z >= 4.0 for (_, _, z), _ in world.boxes_poses())  # dropped from height
        settle(world)
        poses = world.boxes_poses()
        assert len(poses) == 8
        for (x, y, z), _ in poses:
            assert z == pytest.approx(BOX_SIZE_M / 2, abs=0.02)  # resting on the ground
            assert abs(x) <= ARENA_HALF_SIZE_M + TUMBLE_MARGIN_M
            assert abs(y) <= ARENA_HALF_SIZE_M + TUMBLE_MARGIN_M
            assert math.hypot(x, y) > BOX_MIN_START_DISTANCE_M
        for i, ((xi, yi, _), _) in enumerate(poses):
            for (xj, yj, _), _ in poses[:i]:
                assert math.hypot(xi - xj, yi - yj) >= BOX_SIZE_M - 0.01  # none inside another
        velocities = [world.drone_velocity()]
        assert velocities  # the world still reads out after the drop


def test_box_count_follows_the_config(make_world: MakeWorld) -> None:
    assert make_world(seed=1, boxes=3).boxes_poses().__len__() == 3
    assert make_world(seed=1, boxes=0).boxes_poses() == []


@pytest.mark.parametrize("boxes", [-1, MAX_BOXES + 1])
def test_config_refuses_impossible_box_counts(boxes: int) -> None:
    with pytest.raises(ValueError, match="boxes"):
        WorldConfig(seed=1, boxes=boxes)


def test_same_seed_same_world_different_seed_different_world(make_world: MakeWorld) -> None:
    a, b, c = make_world(seed=5), make_world(seed=5), make_world(seed=6)
    assert a.boxes_poses() == b.boxes_poses()
    assert a.boxes_poses() != c.boxes_poses()
    settle(a, 2.0)
    settle(b, 2.0)
    assert a.boxes_poses() == b.boxes_poses()


def test_same_seed_same_inputs_same_trajectory(make_world: MakeWorld) -> None:
    worlds = [make_world(seed=9), make_world(seed=9)]
    for world in worlds:
        stream_setpoint(world, (0.0, 0.0, 3.0), seconds=3.0)
        world.set_cmd_vel(1.0, -0.5, 0.2, 0.3)
        stream_setpoint(world, (2.0, -1.0, 4.0), seconds=2.0, yaw=1.0)
        world.step(PHYSICS_HZ)
    assert worlds[0].drone_pose() == worlds[1].drone_pose()
    assert worlds[0].drone_velocity() == worlds[1].drone_velocity()
    assert worlds[0].boxes_poses() == worlds[1].boxes_poses()


def test_unseeded_worlds_report_their_seed(make_world: MakeWorld) -> None:
    world = make_world()
    again = make_world(seed=world.seed)
    assert world.boxes_poses() == again.boxes_poses()


def test_clock_advances_one_240th_per_step(make_world: MakeWorld) -> None:
    world = make_world(seed=1, boxes=0)
    assert world.time_s == 0.0
    world.step()
    assert world.time_s == pytest.approx(PHYSICS_DT_S)
    world.step(239)
    world.step(0)
    assert world.steps == 240
    assert world.time_s == pytest.approx(1.0)
    with pytest.raises(ValueError, match="n=-1"):
        world.step(-1)


def test_starts_landed_and_stays_put_without_input(make_world: MakeWorld) -> None:
    world = make_world(seed=1)
    settle(world, 2.0)
    (x, y, z), _ = world.drone_pose()
    assert (x, y) == pytest.approx((0.0, 0.0), abs=1e-3)
    assert z <= ON_GROUND_Z_M
    assert world.on_ground
    state = world.drone_state()
    assert state.landed and not state.armed and state.on_ground
    assert state.mode is ControlMode.HOLD
    assert world.tilt_deg() == pytest.approx(0.0, abs=0.1)


def test_reset_puts_the_drone_back_and_drops_new_boxes(make_world: MakeWorld) -> None:
    world = make_world(seed=4)
    first_boxes = world.boxes_poses()
    stream_setpoint(world, (0.0, 0.0, 3.0), seconds=3.0)
    stream_setpoint(world, (5.0, 3.0, 4.0), seconds=2.0)
    assert not world.on_ground
    clock = world.time_s
    world.reset()
    assert world.time_s == clock  # the clock keeps running
    (x, y, z), orientation = world.drone_pose()
    assert (x, y) == (0.0, 0.0)
    assert z <= ON_GROUND_Z_M
    assert orientation == (0.0, 0.0, 0.0, 1.0)
    assert world.drone_velocity() == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert world.drone_state().mode is ControlMode.HOLD  # the setpoint was forgotten
    new_boxes = world.boxes_poses()
    assert len(new_boxes) == len(first_boxes)
    assert new_boxes != first_boxes
    settle(world, 2.0)
    assert world.on_ground and world.drone_state().landed  # controller state cleared: no take-off


def test_resets_are_repeatable_for_a_seed(make_world: MakeWorld) -> None:
    a, b = make_world(seed=11), make_world(seed=11)
    history_a: list[list[Pose]] = []
    history_b: list[list[Pose]] = []
    for world, history in ((a, history_a), (b, history_b)):
        for _ in range(3):
            history.append(world.boxes_poses())
            world.step(10)
            world.reset()
    assert history_a == history_b
    assert len({str(poses) for poses in history_a}) == 3  # each reset drew a new set


@pytest.mark.parametrize(
    ("call", "args", "field"),
    [
        ("set_setpoint", (math.nan, 0.0, 3.0), "x"),
        ("set_setpoint", (0.0, 0.0, 80.0), "z"),
        ("set_setpoint", (0.0, -1e9, 3.0), "y"),
        ("set_cmd_vel", (0.0, math.inf, 0.0), "vy"),
    ],
)
def test_bad_input_raises_and_leaves_the_flight_untouched(
    hovering: World, call: str, args: tuple[float, ...], field: str
) -> None:
    before = hovering.drone_pose()[0]
    with pytest.raises(InvalidCommand, match=field):
        getattr(hovering, call)(*args)
    log = stream_setpoint(hovering, (0.0, 0.0, 3.0), seconds=1.0)
    assert hovering.drone_state().mode is ControlMode.OFFBOARD
    assert math.dist(log.final, before) < 0.05
    assert all(math.isfinite(c) for c in log.final)


def test_cmd_vel_reports_what_it_clamped(make_world: MakeWorld) -> None:
    world = make_world(seed=1, boxes=0)
    assert world.set_cmd_vel(0.0, 20.0, -10.0) == (0.0, 8.0, -3.0, 0.0)


def test_a_closed_world_refuses_to_step(make_world: MakeWorld) -> None:
    world = make_world(seed=1, boxes=0)
    world.close()
    world.close()  # idempotent
    with pytest.raises(RuntimeError, match="closed"):
        world.step()


def test_worlds_are_independent(make_world: MakeWorld) -> None:
    flying, resting = make_world(seed=1, boxes=0), make_world(seed=1, boxes=0)
    stream_setpoint(flying, (0.0, 0.0, 3.0), seconds=2.0)
    resting.step(2 * PHYSICS_HZ)
    assert flying.drone_pose()[0][2] > 2.0
    assert resting.on_ground


def test_context_manager_closes() -> None:
    with World(WorldConfig(seed=1, boxes=0)) as world:
        world.step()
    with pytest.raises(RuntimeError):
        world.drone_pose()
