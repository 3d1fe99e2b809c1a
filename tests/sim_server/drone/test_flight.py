"""Flying: take-off, moves, limits, low-altitude rule, failsafe, teleop, landing."""

from __future__ import annotations

import math

import pytest

from sim_server.drone.commands import ControlMode
from sim_server.drone.limits import (
    HORIZONTAL_CONTROL_MIN_Z_M,
    MAX_SPEED_XY,
    MAX_SPEED_Z,
    ON_GROUND_Z_M,
    STREAM_TIMEOUT_S,
)
from sim_server.drone.world import World
from tests.sim_server.drone.flight import STEPS_PER_SETPOINT, idle, stream_cmd_vel, stream_setpoint

SPEED_TOLERANCE = 0.3  # m/s over the limit, for the velocity loop's own overshoot


def test_takes_off_to_3m_then_moves_6m_sideways_tilting(empty_world: World) -> None:
    climb = stream_setpoint(empty_world, (0.0, 0.0, 3.0), seconds=6.0)
    x, y, z = climb.final
    assert z == pytest.approx(3.0, abs=0.15)
    assert math.hypot(x, y) < 0.05
    assert max(p[2] for p in climb.positions) < 3.0 + 0.3  # overshoots at most a little
    assert climb.max_speed_z <= MAX_SPEED_Z + SPEED_TOLERANCE
    assert empty_world.drone_state().armed

    move = stream_setpoint(empty_world, (6.0, 0.0, 3.0), seconds=6.0)
    x, y, z = move.final
    assert (x, y, z) == pytest.approx((6.0, 0.0, 3.0), abs=0.15)
    assert move.max_tilt_deg > 15.0  # it tilts to accelerate
    assert move.max_speed_xy <= MAX_SPEED_XY + SPEED_TOLERANCE
    peak = max(p[0] for p in move.positions)
    assert 6.0 <= peak < 6.0 + 0.6  # overshoots a little, then settles
    assert empty_world.tilt_deg() < 2.0


def test_long_diagonal_flight_respects_speed_and_tilt_limits(hovering: World) -> None:
    log = stream_setpoint(hovering, (-18.0, 15.0, 20.0), seconds=12.0)
    assert log.final == pytest.approx((-18.0, 15.0, 20.0), abs=0.2)
    assert MAX_SPEED_XY - 1.0 < log.max_speed_xy <= MAX_SPEED_XY + SPEED_TOLERANCE
    assert MAX_SPEED_Z - 0.5 < log.max_speed_z <= MAX_SPEED_Z + SPEED_TOLERANCE
    assert log.max_tilt_deg <= 36.0


def test_below_0_3m_horizontal_setpoints_are_ignored(empty_world: World) -> None:
    low = HORIZONTAL_CONTROL_MIN_Z_M - 0.1
    log = stream_setpoint(empty_world, (8.0, -6.0, low), seconds=5.0)
    x, y, z = log.final
    assert z == pytest.approx(low, abs=0.05)  # it rose...
    assert max(math.hypot(px, py) for px, py, _ in log.positions) < 0.02  # ...without drifting
    assert log.max_tilt_deg < 1.0  # level all the way


def test_below_0_3m_horizontal_cmd_vel_is_ignored(empty_world: World) -> None:
    log = stream_cmd_vel(empty_world, (3.0, 2.0, 0.5, 0.0), seconds=0.4)
    assert all(pz < HORIZONTAL_CONTROL_MIN_Z_M for _, _, pz in log.positions[:3])
    assert max(math.hypot(px, py) for px, py, pz in log.positions if pz < 0.25) < 0.02


def test_failsafe_holds_where_the_stream_stopped(hovering: World) -> None:
    move = stream_setpoint(hovering, (6.0, 0.0, 3.0), seconds=0.5)  # stop mid-move
    stopped_at = move.positions[-2]  # where it was when the last setpoint arrived
    log = idle(hovering, seconds=6.0)
    assert hovering.drone_state().mode is ControlMode.HOLD
    assert log.positions[10][0] > stopped_at[0] + 0.5  # kept going until the timeout...
    assert math.dist(log.final, stopped_at) < 0.1  # ...then went back and holds there
    assert math.dist(log.positions[-30], log.final) < 0.02


def test_stream_counts_as_stopped_after_the_timeout(hovering: World) -> None:
    hovering.set_setpoint(0.0, 0.0, 3.0)
    hovering.step(round((STREAM_TIMEOUT_S - 0.05) * 240))
    assert hovering.drone_state().mode is ControlMode.OFFBOARD
    hovering.step(round(0.1 * 240))
    assert hovering.drone_state().mode is ControlMode.HOLD


def test_cmd_vel_flies_when_no_stream_is_active(hovering: World) -> None:
    idle(hovering, seconds=1.0)  # let the setpoint stream time out
    log = stream_cmd_vel(hovering, (2.0, -1.0, 0.5, 0.0), seconds=3.0)
    assert hovering.drone_state().mode is ControlMode.VELOCITY
    (vx, vy, vz), _ = hovering.drone_velocity()
    assert (vx, vy, vz) == pytest.approx((2.0, -1.0, 0.5), abs=0.2)
    x, y, z = log.final
    assert x > 4.0 and y < -2.0 and z > 3.8
    # a cmd_vel older than the timeout counts as zero: it stops and holds
    stopped = idle(hovering, seconds=5.0)
    assert hovering.drone_state().mode is ControlMode.HOLD
    assert math.dist(stopped.positions[-30], stopped.final) < 0.02


def test_cmd_vel_yaw_rate_turns_the_drone(hovering: World) -> None:
    idle(hovering, seconds=1.0)
    stream_cmd_vel(hovering, (0.0, 0.0, 0.0, 0.5), seconds=2.0)
    _, (_, _, wz) = hovering.drone_velocity()
    assert wz == pytest.approx(0.5, abs=0.1)


def test_cmd_vel_is_ignored_while_a_setpoint_stream_is_active(hovering: World) -> None:
    log = []
    for _ in range(90):
        hovering.set_cmd_vel(5.0, 5.0, 2.0)
        hovering.set_setpoint(0.0, 0.0, 3.0)
        hovering.step(8)
        log.append(hovering.drone_pose()[0])
    assert hovering.drone_state().mode is ControlMode.OFFBOARD
    assert max(math.dist(p, (0.0, 0.0, 3.0)) for p in log) < 0.1


def test_lands_and_stops_the_motors(hovering: World) -> None:
    log = stream_setpoint(hovering, (0.0, 0.0, 0.0), seconds=5.0)
    assert log.final[2] <= ON_GROUND_Z_M
    state = hovering.drone_state()
    assert state.landed and not state.armed and state.on_ground
    assert log.max_speed_z <= MAX_SPEED_Z + SPEED_TOLERANCE


def test_a_landed_drone_stays_down_when_the_stream_stops(hovering: World) -> None:
    # As the control node does: send the landing setpoint until the drone is on the ground, then
    # stop. The last setpoint arrived a little above ON_GROUND_Z_M; the failsafe that takes over
    # must not lift the drone back there (it used to hover at 0.11 m, armed, for good).
    for _ in range(30 * 10):
        hovering.set_setpoint(0.0, 0.0, 0.0)
        hovering.step(STEPS_PER_SETPOINT)
        if hovering.drone_pose()[0][2] <= ON_GROUND_Z_M:
            break
    assert hovering.on_ground
    after = idle(hovering, seconds=3.0)
    assert max(z for _, _, z in after.positions) <= ON_GROUND_Z_M
    state = hovering.drone_state()
    assert state.mode is ControlMode.HOLD
    assert state.landed and not state.armed and state.on_ground
    # and takes off again from there
    again = stream_setpoint(hovering, (0.0, 0.0, 2.0), seconds=4.0)
    assert again.final[2] == pytest.approx(2.0, abs=0.15)


def test_yaw_setpoint_is_followed(hovering: World) -> None:
    stream_setpoint(hovering, (0.0, 0.0, 3.0), seconds=4.0, yaw=math.pi / 2)
    _, (qx, qy, qz, qw) = hovering.drone_pose()
    yaw = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
    assert yaw == pytest.approx(math.pi / 2, abs=0.05)
    assert hovering.drone_pose()[0] == pytest.approx((0.0, 0.0, 3.0), abs=0.1)
