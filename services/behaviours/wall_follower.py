"""Follow a wall on one side at a set distance.

The laser's returns on the wall's side (within 40 degrees of square to it) are fitted with a
straight line, which gives two numbers: how far the wall is, and how the robot is turned
against it. The robot steers to be parallel to the wall, aiming a little towards it when it
is too far and away when too near (the aim grows with the distance error, up to 35 degrees),
so it closes on the set distance without weaving. Something ahead closer than the set distance
(a corner) makes it turn on the spot away from the wall until the way is clear; with no wall
in reach it drives straight on until it finds one.

    skydeck run wall_follower --ros-args -p side:=right -p distance:=0.5
"""

from __future__ import annotations

import math

from services.behaviours.laser import fit_wall, nearest_in_sector, points
from services.behaviours.robot import RobotBehaviour, run_behaviour
from services.runtime import NodeSettings
from services.runtime.parameters import InvalidParameterValueException
from shared_models.sensor_msgs import LaserScan

__all__ = ["WallFollower", "WallFollowing", "main"]

_SIDE_SECTOR_DEG = 40.0
_FRONT_SECTOR_DEG = 20.0
_AIM_GAIN = 2.0  # rad of aim per m of distance error
_MAX_AIM_RAD = math.radians(35.0)
_TURN_GAIN = 2.5  # rad/s per rad of heading error
_MAX_TURN = 1.5  # rad/s
_CORNER_TURN = 1.0  # rad/s, turning away at a corner


class WallFollower:
    """Wall following as a controller: ``update(scan)`` gives the command; ``state`` says what
    it does (``searching``, ``turning``, ``following``)."""

    def __init__(self, side: str = "right", distance: float = 0.5, speed: float = 0.2) -> None:
        self.side = side
        self.distance = distance
        self.speed = speed
        self.state = "searching"
        self.wall_distance = math.inf

    @property
    def side(self) -> str:
        return self._side

    @side.setter
    def side(self, value: str) -> None:
        if value not in ("left", "right"):
            raise InvalidParameterValueException(f"side must be 'left' or 'right', got {value!r}")
        self._side = value
        self._sign = 1.0 if value == "left" else -1.0

    def update(self, scan: LaserScan) -> tuple[float, float]:
        sign = self._sign
        if nearest_in_sector(scan, 0.0, _FRONT_SECTOR_DEG) < self.distance + 0.1:
            self.state = "turning"
            return 0.0, -sign * _CORNER_TURN  # away from the wall's side
        reach = 2.0 * self.distance + 0.5
        near = [(x, y) for x, y in points(scan, sign * 90.0, _SIDE_SECTOR_DEG) if math.hypot(x, y) < reach]
        wall = fit_wall(near)
        if wall is None:
            self.state = "searching"
            self.wall_distance = math.inf
            return self.speed, 0.0
        self.state = "following"
        self.wall_distance = wall.distance
        error = wall.distance - self.distance
        # Seen from the robot, a wall on the right looks turned counter-clockwise (a positive
        # angle) when the robot heads towards it: aim that way when too far, the other when near.
        aim = -sign * max(-_MAX_AIM_RAD, min(_MAX_AIM_RAD, _AIM_GAIN * error))
        turn = max(-_MAX_TURN, min(_MAX_TURN, _TURN_GAIN * (wall.angle - aim)))
        speed = self.speed * max(0.3, math.cos(wall.angle - aim))
        return speed, turn


class WallFollowing(RobotBehaviour):
    """``wall_follower``: a node around :class:`WallFollower`."""

    def __init__(self, namespace: str = "/", settings: NodeSettings | None = None) -> None:
        super().__init__("wall_follower", namespace, settings)
        self.declare_parameter("side", "right")  # which side the wall is on: right or left
        self.declare_parameter("distance", 0.5)  # m, from the laser to the wall
        self.declare_parameter("speed", 0.2)  # m/s
        self.follower = WallFollower(
            self.get_parameter("side").value, self.get_parameter("distance").value, self.get_parameter("speed").value
        )
        self._state = ""

    def control(self) -> tuple[float, float] | None:
        scan = self.sensors.scan
        if scan is None:
            return None
        follower = self.follower
        follower.side = self.get_parameter("side").value
        follower.distance = self.get_parameter("distance").value
        follower.speed = self.get_parameter("speed").value
        command = follower.update(scan)
        if follower.state != self._state:
            self._state = follower.state
            self.get_logger().info("%s", follower.state)
        return command


def main(argv: list[str] | None = None) -> int:
    """``skydeck run wall_follower``."""
    return run_behaviour(WallFollowing, argv, prog="wall_follower", description=__doc__.splitlines()[0])
