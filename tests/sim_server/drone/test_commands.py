"""Checking pilot inputs and choosing which one the drone follows, without physics."""

from __future__ import annotations

import math

import pytest

from sim_server.drone.commands import (
    CommandArbiter,
    ControlMode,
    InvalidCommand,
    check_cmd_vel,
    check_setpoint,
)
from sim_server.drone.limits import (
    MAX_SPEED_XY,
    MAX_SPEED_Z,
    MAX_YAW_RATE,
    ON_GROUND_Z_M,
    STREAM_TIMEOUT_S,
)

DT = 1.0 / 60.0


@pytest.mark.parametrize(
    ("setpoint", "field"),
    [
        ((math.nan, 0.0, 3.0, 0.0), "x"),
        ((0.0, math.inf, 3.0, 0.0), "y"),
        ((0.0, 0.0, -math.inf, 0.0), "z"),
        ((0.0, 0.0, 3.0, math.nan), "yaw"),
        ((25.0, 0.0, 3.0, 0.0), "x"),
        ((0.0, -20.5, 3.0, 0.0), "y"),
        ((0.0, 0.0, -0.5, 0.0), "z"),
        ((0.0, 0.0, 51.0, 0.0), "z"),
        (("three", 0.0, 3.0, 0.0), "x"),
        ((0.0, None, 3.0, 0.0), "y"),
        ((0.0, 0.0, True, 0.0), "z"),
    ],
)
def test_bad_setpoints_are_refused_naming_the_field(
    setpoint: tuple[object, ...], field: str
) -> None:
    with pytest.raises(InvalidCommand) as caught:
        check_setpoint(*setpoint)
    assert caught.value.field == field
    assert f"{field}=" in str(caught.value)
    assert isinstance(caught.value, ValueError)


def test_setpoint_yaw_is_wrapped() -> None:
    assert check_setpoint(1, 2.5, 3, 2.5 * math.pi) == pytest.approx((1.0, 2.5, 3.0, math.pi / 2))


@pytest.mark.parametrize("field", ["vx", "vy", "vz", "yaw_rate"])
def test_non_finite_cmd_vel_is_refused(field: str) -> None:
    values = dict.fromkeys(("vx", "vy", "vz", "yaw_rate"), 0.0)
    values[field] = math.nan
    with pytest.raises(InvalidCommand, match=field):
        check_cmd_vel(**values)


def test_cmd_vel_is_clamped_to_the_limits() -> None:
    vx, vy, vz, rate = check_cmd_vel(30.0, 40.0, -9.0, 100.0)
    assert math.hypot(vx, vy) == pytest.approx(MAX_SPEED_XY)
    assert vx / vy == pytest.approx(0.75)  # direction kept
    assert vz == -MAX_SPEED_Z
    assert rate == MAX_YAW_RATE


def test_a_fresh_setpoint_stream_wins() -> None:
    arbiter = CommandArbiter(0.0, 0.0, 0.06, 0.0)
    arbiter.set_setpoint(1.0, 4.0, 5.0, 3.0, 0.0, drone_pose=(1.5, 1.6, 2.2, 0.3))
    arbiter.set_cmd_vel(1.0, 2.0, 0.0, 0.0, 0.0)
    ref = arbiter.update(1.2, DT, 0.0, 0.0, 1.0, 0.0)
    assert arbiter.mode is ControlMode.OFFBOARD
    assert (ref.x, ref.y, ref.z, ref.vx) == (4.0, 5.0, 3.0, 0.0)


def test_failsafe_holds_where_the_drone_was_when_the_stream_stopped() -> None:
    arbiter = CommandArbiter(0.0, 0.0, 0.06, 0.0)
    arbiter.set_setpoint(1.0, 4.0, 5.0, 3.0, 0.0, drone_pose=(1.5, 1.6, 2.2, 0.3))
    arbiter.update(1.0 + STREAM_TIMEOUT_S, DT, 1.0, 1.0, 2.0, 0.0)
    assert arbiter.mode is ControlMode.OFFBOARD
    ref = arbiter.update(1.0 + STREAM_TIMEOUT_S + DT, DT, 2.5, 2.6, 2.8, 0.0)
    assert arbiter.mode is ControlMode.HOLD
    assert (ref.x, ref.y, ref.z, ref.yaw) == (1.5, 1.6, 2.2, 0.3)
    ref = arbiter.update(5.0, DT, 2.0, 2.0, 2.5, 0.0)  # holds the same point later on
    assert (ref.x, ref.y, ref.z) == (1.5, 1.6, 2.2)


def test_failsafe_keeps_a_drone_on_the_ground_there() -> None:
    arbiter = CommandArbiter(0.0, 0.0, 3.0, 0.0)
    # The landing setpoint's last frame arrived just above the ground; the drone touched down.
    arbiter.set_setpoint(1.0, 1.0, 2.0, 0.0, 0.0, drone_pose=(1.0, 2.0, 0.12, 0.0))
    arbiter.update(1.0 + STREAM_TIMEOUT_S, DT, 1.0, 2.0, 0.07, 0.0)
    assert arbiter.mode is ControlMode.OFFBOARD
    ref = arbiter.update(1.0 + STREAM_TIMEOUT_S + DT, DT, 1.01, 2.02, 0.06, 0.1)
    assert arbiter.mode is ControlMode.HOLD
    assert (ref.x, ref.y, ref.z, ref.yaw) == (1.01, 2.02, 0.06, 0.1)  # where it stands
    assert ref.z <= ON_GROUND_Z_M and ref.vz == 0.0  # so the motors stay off
    ref = arbiter.update(5.0, DT, 1.01, 2.02, 0.06, 0.1)
    assert ref.z == 0.06


def test_cmd_vel_moves_the_target_and_stale_cmd_vel_counts_as_zero() -> None:
    arbiter = CommandArbiter(0.0, 0.0, 3.0, 0.0)
    arbiter.set_cmd_vel(0.0, 1.2, 0.0, 0.0, 0.0)
    ref = arbiter.update(0.1, DT, 0.0, 0.0, 3.0, 0.0)
    assert arbiter.mode is ControlMode.VELOCITY
    assert ref.vx == 1.2
    assert ref.x == pytest.approx(1.2 * DT)
    ref = arbiter.update(STREAM_TIMEOUT_S + 0.1, DT, 0.3, 0.0, 3.0, 0.0)
    assert arbiter.mode is ControlMode.HOLD
    assert ref.vx == 0.0


def test_cmd_vel_target_stays_on_a_leash() -> None:
    arbiter = CommandArbiter(0.0, 0.0, 3.0, 0.0)
    arbiter.set_cmd_vel(0.0, 8.0, 0.0, 0.0, 0.0)
    for i in range(100):
        ref = arbiter.update(i * DT / 10, DT, 0.0, 0.0, 3.0, 0.0)
    assert ref.x <= 1.0


def test_horizontal_cmd_vel_is_ignored_near_the_ground() -> None:
    arbiter = CommandArbiter(0.0, 0.0, 0.06, 0.0)
    arbiter.set_cmd_vel(0.0, 3.0, 3.0, 1.0, 0.0)
    ref = arbiter.update(0.1, DT, 0.0, 0.0, 0.06, 0.0)
    assert (ref.x, ref.y, ref.vx, ref.vy) == (0.0, 0.0, 0.0, 0.0)
    assert ref.vz == 1.0
    assert ref.z > 0.06


def test_refused_input_changes_nothing() -> None:
    arbiter = CommandArbiter(0.0, 0.0, 0.06, 0.0)
    arbiter.set_setpoint(1.0, 4.0, 5.0, 3.0, 0.0, drone_pose=(1.5, 1.6, 2.2, 0.3))
    with pytest.raises(InvalidCommand):
        arbiter.set_setpoint(2.0, 1.0, 1.0, math.nan, 0.0, drone_pose=(9.0, 9.0, 9.0, 0.0))
    with pytest.raises(InvalidCommand):
        arbiter.set_cmd_vel(2.0, math.inf, 0.0, 0.0, 0.0)
    assert arbiter.setpoint == (4.0, 5.0, 3.0, 0.0)
    assert arbiter.setpoint_time_s == 1.0
    assert arbiter.cmd_vel == (0.0, 0.0, 0.0, 0.0)
    assert arbiter.failsafe_hold == (1.5, 1.6, 2.2, 0.3)
