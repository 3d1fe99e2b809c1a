"""The cascaded controller and mixer as pure math, without the physics engine."""

from __future__ import annotations

import math

import pytest

from sim_server.drone.airframe import IRIS, ROTOR_SPIN
from sim_server.drone.controller import CascadedController, Mixer, Reference
from sim_server.drone.limits import GRAVITY_M_S2, MAX_SPEED_XY, MAX_SPEED_Z, MAX_TILT_DEG

LEVEL = (0.0, 0.0, 0.0, 1.0)
STILL = (0.0, 0.0, 0.0)
DT = 1.0 / 60.0


def torques_of(thrusts: tuple[float, ...]) -> tuple[float, float, float, float]:
    """Collective and body torques that four rotor thrusts produce on the airframe."""
    collective = sum(thrusts)
    roll = sum(t * y for t, (_, y, _) in zip(thrusts, IRIS.rotor_positions_m, strict=True))
    pitch = sum(-t * x for t, (x, _, _) in zip(thrusts, IRIS.rotor_positions_m, strict=True))
    yaw = IRIS.moment_constant_m * sum(t * s for t, s in zip(thrusts, ROTOR_SPIN, strict=True))
    return collective, roll, pitch, yaw


def test_mixer_hover_gives_equal_thrusts() -> None:
    *thrusts, yaw_torque = Mixer().mix(IRIS.weight_n, 0.0, 0.0, 0.0)
    assert thrusts == pytest.approx([IRIS.weight_n / 4] * 4)
    assert yaw_torque == pytest.approx(0.0)


@pytest.mark.parametrize("torques", [(0.3, 0.0, 0.0), (0.0, -0.4, 0.0), (0.1, 0.2, 0.05)])
def test_mixer_inverts_the_airframe_when_unsaturated(torques: tuple[float, float, float]) -> None:
    *thrusts, yaw_torque = Mixer().mix(IRIS.weight_n, *torques)
    collective, roll, pitch, yaw = torques_of(tuple(thrusts))
    assert (collective, roll, pitch, yaw) == pytest.approx((IRIS.weight_n, *torques), abs=1e-9)
    assert yaw_torque == pytest.approx(yaw)


def test_mixer_keeps_thrusts_in_range_and_roll_over_yaw_when_saturated() -> None:
    *thrusts, _ = Mixer().mix(4 * IRIS.max_rotor_thrust_n, 5.0, 0.0, 3.0)
    assert all(0.0 <= t <= IRIS.max_rotor_thrust_n for t in thrusts)
    _, roll, _, yaw = torques_of(tuple(thrusts))
    assert roll > 0.5  # most of the available roll authority survives
    assert abs(yaw) < 1e-9  # yaw is given up first


def test_idle_on_the_ground_with_a_ground_target() -> None:
    ctl = CascadedController()
    ctl.update_position(Reference(z=0.0), 0.0, 0.0, IRIS.rest_z_m, *STILL, DT)
    assert ctl.idle
    assert ctl.update_attitude(*LEVEL, *STILL) == (0.0, 0.0, 0.0, 0.0, 0.0)


def test_takes_off_level_when_low_even_with_a_horizontal_target() -> None:
    ctl = CascadedController()
    ctl.update_position(Reference(x=10.0, y=-5.0, z=3.0), 0.0, 0.0, 0.06, *STILL, DT)
    assert not ctl.idle
    assert ctl.velocity_setpoint[:2] == (0.0, 0.0)
    assert ctl.accel_setpoint[:2] == (0.0, 0.0)
    *thrusts, _ = ctl.update_attitude(*LEVEL, *STILL)
    assert sum(thrusts) > IRIS.weight_n  # climbing
    assert max(thrusts) - min(thrusts) == pytest.approx(0.0, abs=1e-9)  # level


def test_far_target_saturates_speed_and_tilt() -> None:
    ctl = CascadedController()
    ctl.update_position(Reference(x=100.0, y=100.0, z=40.0), 0.0, 0.0, 3.0, *STILL, DT)
    svx, svy, svz = ctl.velocity_setpoint
    assert math.hypot(svx, svy) == pytest.approx(MAX_SPEED_XY)
    assert svz == pytest.approx(MAX_SPEED_Z)
    ax, ay, az = ctl.accel_setpoint
    tilt = math.degrees(math.atan2(math.hypot(ax, ay), az + GRAVITY_M_S2))
    assert tilt == pytest.approx(MAX_TILT_DEG)


def test_forward_target_pitches_nose_down() -> None:
    ctl = CascadedController()
    ctl.update_position(Reference(x=5.0, z=3.0), 0.0, 0.0, 3.0, *STILL, DT)
    front_right, back_left, front_left, back_right, _ = ctl.update_attitude(*LEVEL, *STILL)
    assert back_left + back_right > front_left + front_right


def test_rolled_drone_is_levelled() -> None:
    ctl = CascadedController()
    ctl.update_position(Reference(z=3.0), 0.0, 0.0, 3.0, *STILL, DT)
    half = math.radians(10.0) / 2  # rolled 10 degrees right side up: left side down is +roll
    thrusts = ctl.update_attitude(math.sin(half), 0.0, 0.0, math.cos(half), *STILL)
    _, roll, _, _ = torques_of(thrusts[:4])
    assert roll < 0.0


def test_yaw_error_turns_toward_the_target_yaw() -> None:
    ctl = CascadedController()
    ctl.update_position(Reference(z=3.0, yaw=0.5), 0.0, 0.0, 3.0, *STILL, DT)
    *_, yaw_torque = ctl.update_attitude(*LEVEL, *STILL)
    assert yaw_torque > 0.0


def test_reset_clears_integrators() -> None:
    ctl = CascadedController()
    for _ in range(200):
        ctl.update_position(Reference(z=3.0), 0.0, 0.0, 2.9, 0.0, 0.0, 0.0, DT)
    ctl.reset()
    assert ctl.idle
    ctl.update_position(Reference(z=3.0), 0.0, 0.0, 3.0, *STILL, DT)
    assert ctl.accel_setpoint == pytest.approx((0.0, 0.0, 0.0))
