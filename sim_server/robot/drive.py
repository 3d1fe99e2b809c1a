"""Differential drive: checking a body-frame velocity command, turning it into wheel speeds,
and wheel odometry from the encoders.

Pure arithmetic (no PyBullet), so the kinematics can be tested on their own. Odometry works as
a real robot's does: from how far each wheel turned between two readings (encoder ticks), along
an arc, so it drifts only where the wheels slip (a push against a wall, a hard start).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sim_server.checks import finite_number
from sim_server.robot.limits import (
    MAX_ANGULAR_SPEED,
    MAX_LINEAR_SPEED,
    WHEEL_RADIUS_M,
    WHEEL_SEPARATION_M,
)

__all__ = ["WheelOdometry", "check_cmd_vel", "wheel_speeds"]


def check_cmd_vel(linear_x: object, angular_z: object) -> tuple[float, float]:
    """A /cmd_vel's forward speed (m/s) and turn rate (rad/s), clamped to the robot's limits.

    Raises InvalidCommand for a value that is not a finite number; nothing changes then.
    """
    v = finite_number("cmd_vel", "linear.x", linear_x)
    w = finite_number("cmd_vel", "angular.z", angular_z)
    return (
        max(-MAX_LINEAR_SPEED, min(MAX_LINEAR_SPEED, v)),
        max(-MAX_ANGULAR_SPEED, min(MAX_ANGULAR_SPEED, w)),
    )


def wheel_speeds(v: float, w: float) -> tuple[float, float]:
    """The left and right wheel rates (rad/s, positive rolls forward) for forward speed ``v``
    and turn rate ``w`` (counter-clockwise)."""
    half_track = WHEEL_SEPARATION_M / 2.0
    return (v - w * half_track) / WHEEL_RADIUS_M, (v + w * half_track) / WHEEL_RADIUS_M


@dataclass(slots=True)
class WheelOdometry:
    """Dead reckoning from the wheel encoders, in the ``odom`` frame (the robot's start).

    ``update`` takes the wheel angles (rad, as the encoders count them) and rates; the pose
    integrates the angle changes along an arc, the twist comes from the rates.
    """

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0
    linear: float = 0.0
    """Forward speed, m/s (body frame)."""
    angular: float = 0.0
    """Turn rate, rad/s."""
    _left: float | None = None
    _right: float | None = None

    def update(self, left: float, right: float, left_rate: float, right_rate: float) -> None:
        """Take one reading of the encoders (angles, rad) and wheel rates (rad/s)."""
        r = WHEEL_RADIUS_M
        self.linear = r * (left_rate + right_rate) / 2.0
        self.angular = r * (right_rate - left_rate) / WHEEL_SEPARATION_M
        if self._left is None or self._right is None:
            self._left, self._right = left, right
            return
        d_left = r * (left - self._left)
        d_right = r * (right - self._right)
        self._left, self._right = left, right
        distance = (d_left + d_right) / 2.0
        turn = (d_right - d_left) / WHEEL_SEPARATION_M
        # Along an arc: the chord points at the heading halfway through the turn, and is
        # shorter than the arc by sin(t/2) / (t/2).
        half = turn / 2.0
        chord = distance * (math.sin(half) / half if half else 1.0)
        heading = self.yaw + half
        self.x += chord * math.cos(heading)
        self.y += chord * math.sin(heading)
        self.yaw = math.remainder(self.yaw + turn, math.tau)
