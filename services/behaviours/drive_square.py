"""Drive a square by odometry, not by timing.

The robot drives a side of ``side`` metres, turns 90 degrees counter-clockwise on the spot,
four times, and stops where it started. Distances and angles come from ``/odom``: a leg ends
when the robot is ``side`` metres from the leg's start, holding the leg's heading on the way
(a small proportional correction), and a turn ends when the heading is 90 degrees on from the
last leg's, slowing down as it gets there so as not to overshoot. Timing a square ("drive 5 s
at 0.2 m/s") misses by whatever the acceleration and the latency took; odometry does not.

    skydeck run drive_square --ros-args -p side:=1.5 -p speed:=0.2
"""

from __future__ import annotations

import math

from services.behaviours.robot import Pose2D, RobotBehaviour, run_behaviour
from services.runtime import NodeSettings

__all__ = ["DriveSquare", "SquareDriver", "main"]

_HEADING_GAIN = 2.0  # rad/s of correction per rad of heading error on a leg
_TURN_GAIN = 3.0  # rad/s per rad left to turn, near the end of a turn
_MIN_TURN_RATE = 0.15
_TURN_DONE_RAD = math.radians(0.5)


class SquareDriver:
    """The square as a controller: ``update(pose)`` gives the command, ``done`` when finished."""

    def __init__(self, side: float, speed: float, turn_rate: float) -> None:
        self.side = side
        self.speed = speed
        self.turn_rate = turn_rate
        self.legs_done = 0
        self.turning = False
        self.done = False
        self._start: Pose2D | None = None
        self._heading = 0.0

    def update(self, pose: Pose2D) -> tuple[float, float]:
        if self.done:
            return 0.0, 0.0
        if self._start is None:
            self._start, self._heading = pose, pose.yaw
        if self.turning:
            left = math.remainder(self._heading - pose.yaw, math.tau)
            if abs(left) <= _TURN_DONE_RAD:
                self.turning = False
                self._start = pose
                return 0.0, 0.0
            rate = max(_MIN_TURN_RATE, min(self.turn_rate, _TURN_GAIN * abs(left)))
            return 0.0, math.copysign(rate, left)
        travelled = self._start.distance_to(pose.x, pose.y)
        if travelled >= self.side:
            self.legs_done += 1
            if self.legs_done == 4:
                self.done = True
            else:
                self.turning = True
                self._heading = math.remainder(self._heading + math.pi / 2.0, math.tau)
            return 0.0, 0.0
        # Slow down over the last 10 cm, so the leg ends where it should.
        speed = min(self.speed, max(0.05, 2.0 * (self.side - travelled)))
        heading_error = math.remainder(self._heading - pose.yaw, math.tau)
        return speed, _HEADING_GAIN * heading_error


class DriveSquare(RobotBehaviour):
    """``drive_square``: one square, then it stops and says so on /rosout."""

    def __init__(self, namespace: str = "/", settings: NodeSettings | None = None) -> None:
        super().__init__("drive_square", namespace, settings)
        self.declare_parameter("side", 1.0)  # m
        self.declare_parameter("speed", 0.2)  # m/s along a side
        self.declare_parameter("turn_rate", 0.6)  # rad/s, turning on the spot
        self.square = SquareDriver(
            self.get_parameter("side").value,
            self.get_parameter("speed").value,
            self.get_parameter("turn_rate").value,
        )
        self._reported = False

    def control(self) -> tuple[float, float] | None:
        pose = self.sensors.pose
        if pose is None:
            return None
        self.square.side = self.get_parameter("side").value  # tunable while it drives
        self.square.speed = self.get_parameter("speed").value
        self.square.turn_rate = self.get_parameter("turn_rate").value
        command = self.square.update(pose)
        if self.square.done:
            if self._reported:
                return None  # stopped; the watchdog keeps it so
            self._reported = True
            self.get_logger().info("square done: back at (%.2f, %.2f) by odometry", pose.x, pose.y)
        return command


def main(argv: list[str] | None = None) -> int:
    """``skydeck run drive_square``."""
    return run_behaviour(DriveSquare, argv, prog="drive_square", description=__doc__.splitlines()[0])
