"""Pilot inputs: checking them, and choosing which one the drone follows.

Two inputs reach the drone, as in the workshop's fake MAVROS:

- a setpoint stream (position + yaw, re-sent at ~30 Hz): offboard control, wins while fresh;
- cmd_vel (world-frame velocity + yaw rate, for teleop): followed only while no setpoint
  stream is active, and counts as zero once older than STREAM_TIMEOUT_S.

When the setpoint stream stops for STREAM_TIMEOUT_S (sim time) the offboard failsafe engages:
the drone goes back to, and holds, the position it had when the last setpoint arrived (where
the stream stopped); a drone standing on the ground by then (landed) stays where it stands, with
its motors off. With neither input it simply holds. Bad input raises
:class:`InvalidCommand` before anything changes, so nothing non-finite reaches the physics.
"""

from __future__ import annotations

import enum
import math

from sim_server.checks import InvalidCommand, finite_number
from sim_server.drone.controller import Reference
from sim_server.drone.limits import (
    CEILING_M,
    FLY_HALF_SIZE_M,
    HORIZONTAL_CONTROL_MIN_Z_M,
    MAX_SPEED_XY,
    MAX_SPEED_Z,
    MAX_YAW_RATE,
    ON_GROUND_Z_M,
    STREAM_TIMEOUT_S,
)

__all__ = ["CommandArbiter", "ControlMode", "InvalidCommand", "check_cmd_vel", "check_setpoint"]

_LEASH_M = 1.0
"""How far a cmd_vel-driven target may run ahead of a drone that cannot keep up."""


class ControlMode(enum.Enum):
    """Which input the drone follows; the values are PX4's mode names, as MAVROS reports them."""

    OFFBOARD = "OFFBOARD"
    """Following a fresh setpoint stream."""
    VELOCITY = "POSCTL"
    """Following cmd_vel (teleop)."""
    HOLD = "AUTO.LOITER"
    """No fresh input: holding position (also the offboard failsafe)."""


def _within(command: str, field: str, value: float, low: float, high: float) -> float:
    if not low <= value <= high:
        raise InvalidCommand(command, field, value, f"is outside [{low:g}, {high:g}]")
    return value


def check_setpoint(
    x: object, y: object, z: object, yaw: object
) -> tuple[float, float, float, float]:
    """Validate a setpoint; returns it as floats with yaw wrapped to [-pi, pi]."""
    fx = _within("setpoint", "x", finite_number("setpoint", "x", x), -FLY_HALF_SIZE_M, FLY_HALF_SIZE_M)
    fy = _within("setpoint", "y", finite_number("setpoint", "y", y), -FLY_HALF_SIZE_M, FLY_HALF_SIZE_M)
    fz = _within("setpoint", "z", finite_number("setpoint", "z", z), 0.0, CEILING_M)
    fyaw = math.remainder(finite_number("setpoint", "yaw", yaw), math.tau)
    return fx, fy, fz, fyaw


def check_cmd_vel(
    vx: object, vy: object, vz: object, yaw_rate: object
) -> tuple[float, float, float, float]:
    """Validate a velocity command; returns it clamped to the speed limits."""
    fvx = finite_number("cmd_vel", "vx", vx)
    fvy = finite_number("cmd_vel", "vy", vy)
    fvz = finite_number("cmd_vel", "vz", vz)
    frate = finite_number("cmd_vel", "yaw_rate", yaw_rate)
    speed = math.hypot(fvx, fvy)
    if speed > MAX_SPEED_XY:
        fvx *= MAX_SPEED_XY / speed
        fvy *= MAX_SPEED_XY / speed
    fvz = max(-MAX_SPEED_Z, min(MAX_SPEED_Z, fvz))
    frate = max(-MAX_YAW_RATE, min(MAX_YAW_RATE, frate))
    return fvx, fvy, fvz, frate


class CommandArbiter:
    """Holds the latest inputs and turns them into the controller's :class:`Reference`."""

    def __init__(self, x: float, y: float, z: float, yaw: float) -> None:
        self.reset(x, y, z, yaw)

    def reset(self, x: float, y: float, z: float, yaw: float) -> None:
        """Drop every input and hold (x, y, z, yaw)."""
        self.mode = ControlMode.HOLD
        self.setpoint: tuple[float, float, float, float] | None = None
        self.setpoint_time_s = -math.inf
        self.failsafe_hold = (x, y, z, yaw)
        """The drone's pose when the latest setpoint arrived: held if the stream stops."""
        self.cmd_vel = (0.0, 0.0, 0.0, 0.0)
        self.cmd_vel_time_s = -math.inf
        self.reference = Reference(x=x, y=y, z=z, yaw=yaw)

    def set_setpoint(
        self,
        now_s: float,
        x: object,
        y: object,
        z: object,
        yaw: object,
        *,
        drone_pose: tuple[float, float, float, float],
    ) -> None:
        """Take a position setpoint that arrived at sim time ``now_s``, when the drone was at
        ``drone_pose`` (x, y, z, yaw)."""
        self.setpoint = check_setpoint(x, y, z, yaw)
        self.setpoint_time_s = now_s
        self.failsafe_hold = drone_pose

    def set_cmd_vel(
        self, now_s: float, vx: object, vy: object, vz: object, yaw_rate: object
    ) -> tuple[float, float, float, float]:
        """Take a velocity command that arrived at ``now_s``; returns it as clamped."""
        self.cmd_vel = check_cmd_vel(vx, vy, vz, yaw_rate)
        self.cmd_vel_time_s = now_s
        return self.cmd_vel

    def update(
        self, now_s: float, dt_s: float, px: float, py: float, pz: float, yaw: float
    ) -> Reference:
        """Choose the input to follow at ``now_s`` and return the reference for the controller."""
        ref = self.reference
        if self.setpoint is not None and now_s - self.setpoint_time_s <= STREAM_TIMEOUT_S:
            self.mode = ControlMode.OFFBOARD
            ref.x, ref.y, ref.z, ref.yaw = self.setpoint
            ref.vx = ref.vy = ref.vz = ref.yaw_rate = 0.0
            return ref
        if self.mode is ControlMode.OFFBOARD:  # the stream has stopped: failsafe
            if pz <= ON_GROUND_Z_M:
                # On the ground (landed): it stays where it stands, motors off. The last setpoint
                # of a landing arrived a little above the ground; holding there lifted it again.
                ref.x, ref.y, ref.z, ref.yaw = px, py, pz, yaw
            else:
                ref.x, ref.y, ref.z, ref.yaw = self.failsafe_hold
        if now_s - self.cmd_vel_time_s <= STREAM_TIMEOUT_S:
            vx, vy, vz, yaw_rate = self.cmd_vel
        else:
            vx = vy = vz = yaw_rate = 0.0
        low = pz < HORIZONTAL_CONTROL_MIN_Z_M
        if low:  # horizontal commands are ignored near the ground; hold where it stands
            vx = vy = 0.0
            ref.x, ref.y = px, py
            if pz <= ON_GROUND_Z_M:  # standing: motors off, heading is what it is
                yaw_rate = 0.0
                ref.yaw = yaw
        moving = vx != 0.0 or vy != 0.0 or vz != 0.0 or yaw_rate != 0.0
        self.mode = ControlMode.VELOCITY if moving else ControlMode.HOLD
        # A carrot: the target moves with the command, on a leash so it never runs far ahead.
        if vx != 0.0 or vy != 0.0:
            ref.x = _leash(ref.x + vx * dt_s, px, -FLY_HALF_SIZE_M, FLY_HALF_SIZE_M)
            ref.y = _leash(ref.y + vy * dt_s, py, -FLY_HALF_SIZE_M, FLY_HALF_SIZE_M)
        if vz != 0.0:
            ref.z = _leash(ref.z + vz * dt_s, pz, 0.0, CEILING_M)
        ref.yaw = math.remainder(ref.yaw + yaw_rate * dt_s, math.tau)
        ref.vx, ref.vy, ref.vz, ref.yaw_rate = vx, vy, vz, yaw_rate
        return ref


def _leash(target: float, actual: float, low: float, high: float) -> float:
    target = max(actual - _LEASH_M, min(actual + _LEASH_M, target))
    return max(low, min(high, target))
