"""Differential-drive arithmetic: command checks, wheel speeds, encoder odometry."""

from __future__ import annotations

import math

import pytest

from sim_server.drone.commands import InvalidCommand
from sim_server.robot.drive import WheelOdometry, check_cmd_vel, wheel_speeds
from sim_server.robot.limits import (
    MAX_ANGULAR_SPEED,
    MAX_LINEAR_SPEED,
    WHEEL_RADIUS_M,
    WHEEL_SEPARATION_M,
)


def test_commands_beyond_the_limits_are_clamped() -> None:
    assert check_cmd_vel(0.1, -0.5) == (0.1, -0.5)
    assert check_cmd_vel(5.0, 10.0) == (MAX_LINEAR_SPEED, MAX_ANGULAR_SPEED)
    assert check_cmd_vel(-5.0, -10.0) == (-MAX_LINEAR_SPEED, -MAX_ANGULAR_SPEED)
    assert check_cmd_vel(1, 0) == (MAX_LINEAR_SPEED, 0.0)  # integers are numbers


@pytest.mark.parametrize(
    ("linear", "angular", "field"),
    [(math.nan, 0.0, "linear.x"), (0.0, math.inf, "angular.z"), (-math.inf, 0.0, "linear.x"),
     ("fast", 0.0, "linear.x"), (0.0, None, "angular.z"), (True, 0.0, "linear.x")],
)  # fmt: skip
def test_non_numbers_are_refused_naming_the_field(linear: object, angular: object, field: str) -> None:
    with pytest.raises(InvalidCommand, match=rf"cmd_vel: {field}=") as caught:
        check_cmd_vel(linear, angular)
    assert caught.value.field == field


def test_wheel_speeds_of_straight_turning_and_arcing() -> None:
    assert wheel_speeds(0.2, 0.0) == pytest.approx((0.2 / WHEEL_RADIUS_M,) * 2)
    left, right = wheel_speeds(0.0, 1.0)  # counter-clockwise: the right wheel forward
    assert right == pytest.approx(-left) and right * WHEEL_RADIUS_M == pytest.approx(WHEEL_SEPARATION_M / 2)
    left, right = wheel_speeds(0.2, 0.5)
    assert (left + right) / 2 * WHEEL_RADIUS_M == pytest.approx(0.2)
    assert (right - left) * WHEEL_RADIUS_M / WHEEL_SEPARATION_M == pytest.approx(0.5)


def test_odometry_follows_an_arc_exactly_from_the_encoders() -> None:
    odometry = WheelOdometry()
    v, w, dt = 0.2, 0.8, 1 / 60
    left_rate, right_rate = wheel_speeds(v, w)
    odometry.update(0.0, 0.0, left_rate, right_rate)  # the first reading is the encoders' zero
    left = right = 0.0
    steps = 240  # 4 s
    for _ in range(steps):
        left += left_rate * dt
        right += right_rate * dt
        odometry.update(left, right, left_rate, right_rate)
    t = steps * dt
    radius = v / w
    assert odometry.x == pytest.approx(radius * math.sin(w * t), abs=1e-9)
    assert odometry.y == pytest.approx(radius * (1 - math.cos(w * t)), abs=1e-9)
    assert odometry.yaw == pytest.approx(math.remainder(w * t, math.tau), abs=1e-12)
    assert (odometry.linear, odometry.angular) == pytest.approx((v, w))

