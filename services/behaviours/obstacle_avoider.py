"""Drive to a goal point, around whatever the laser sees in the way.

Each tick the avoider looks at headings all round the robot, every 5 degrees, and keeps those
along which a lane as wide as the robot (plus ``margin`` each side) is clear of laser returns
for ``lookahead`` metres (less when the goal is nearer). Of the clear headings it takes the
one closest to the goal's direction, with a small preference for the heading it took last (so
it commits to one side of an obstacle instead of dithering), turns towards it and drives,
slower the more it has to turn. The goal is in the odom frame (where the robot started, facing
+x); within ``tolerance`` of it the robot stops and says so.

    skydeck run obstacle_avoider --ros-args -p goal_x:=3.0 -p goal_y:=-2.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from services.behaviours.laser import points
from services.behaviours.robot import Pose2D, RobotBehaviour, run_behaviour
from services.runtime import NodeSettings
from shared_models.sensor_msgs import LaserScan
from sim_server.robot.limits import ROBOT_RADIUS_M

__all__ = ["GoalSeeker", "ObstacleAvoider", "clear_headings", "main"]

_HEADINGS = [math.radians(d) for d in range(-180, 180, 5)]
_STICK_WEIGHT = 0.3  # how much the last heading is preferred, against the goal's direction
_TURN_GAIN = 2.0
_MAX_TURN = 1.5
_DRIVE_WITHIN_RAD = math.radians(60.0)  # beyond this, turn on the spot first


def clear_headings(
    found: list[tuple[float, float]], lane_half_width: float, lookahead: float
) -> list[float]:
    """The headings (rad, robot frame) along which no point lies in a lane of that half width,
    from the robot out to ``lookahead`` metres."""
    near = [(x, y) for x, y in found if math.hypot(x, y) <= lookahead + lane_half_width]
    clear = []
    for heading in _HEADINGS:
        c, s = math.cos(heading), math.sin(heading)
        blocked = False
        for x, y in near:
            along = c * x + s * y
            if -lane_half_width < along < lookahead and abs(-s * x + c * y) < lane_half_width:
                blocked = True
                break
        if not blocked:
            clear.append(heading)
    return clear


@dataclass
class GoalSeeker:
    """Driving to a goal around obstacles, as a controller: ``update(scan, pose)``; ``reached``."""

    goal: tuple[float, float]
    speed: float = 0.2
    margin: float = 0.12
    lookahead: float = 0.8
    tolerance: float = 0.1
    reached: bool = field(default=False, init=False)
    state: str = field(default="driving", init=False)
    _last: float | None = field(default=None, init=False, repr=False)
    """The heading taken last, in the odom frame (the robot's own turning is no change)."""

    def update(self, scan: LaserScan, pose: Pose2D) -> tuple[float, float]:
        distance = pose.distance_to(*self.goal)
        if distance <= self.tolerance:
            self.reached = True
            self.state = "reached"
            return 0.0, 0.0
        self.reached = False
        to_goal = pose.bearing_to(*self.goal)
        lane = ROBOT_RADIUS_M + self.margin
        clear = clear_headings(points(scan), lane, min(self.lookahead, distance))
        if not clear:
            self.state = "boxed in"
            return 0.0, _MAX_TURN / 2.0  # turn until a way opens

        def cost(heading: float) -> float:
            off_goal = abs(math.remainder(heading - to_goal, math.tau))
            last = self._last
            off_last = 0.0 if last is None else abs(math.remainder(pose.yaw + heading - last, math.tau))
            return off_goal + _STICK_WEIGHT * off_last

        heading = min(clear, key=cost)
        self._last = pose.yaw + heading
        self.state = "driving" if abs(math.remainder(heading - to_goal, math.tau)) < 0.05 else "avoiding"
        turn = max(-_MAX_TURN, min(_MAX_TURN, _TURN_GAIN * heading))
        if abs(heading) > _DRIVE_WITHIN_RAD:
            return 0.0, turn
        speed = min(self.speed, max(0.05, distance)) * math.cos(heading)
        return speed, turn


class ObstacleAvoider(RobotBehaviour):
    """``obstacle_avoider``: a node around :class:`GoalSeeker`."""

    def __init__(self, namespace: str = "/", settings: NodeSettings | None = None) -> None:
        super().__init__("obstacle_avoider", namespace, settings)
        self.declare_parameter("goal_x", 3.0)  # m, odom frame
        self.declare_parameter("goal_y", 0.0)
        self.declare_parameter("speed", 0.2)  # m/s
        self.declare_parameter("margin", 0.12)  # m of room kept each side of the robot
        self.declare_parameter("lookahead", 0.8)  # m of clear lane wanted ahead
        self.declare_parameter("tolerance", 0.1)  # m: this close is there
        self.seeker = GoalSeeker(self._goal())
        self._state = ""

    def _goal(self) -> tuple[float, float]:
        return self.get_parameter("goal_x").value, self.get_parameter("goal_y").value

    def control(self) -> tuple[float, float] | None:
        scan, pose = self.sensors.scan, self.sensors.pose
        if scan is None or pose is None:
            return None
        seeker = self.seeker
        seeker.goal = self._goal()
        seeker.speed = self.get_parameter("speed").value
        seeker.margin = self.get_parameter("margin").value
        seeker.lookahead = self.get_parameter("lookahead").value
        seeker.tolerance = self.get_parameter("tolerance").value
        command = seeker.update(scan, pose)
        if seeker.state != self._state:
            self._state = seeker.state
            self.get_logger().info("%s (goal %.2f, %.2f; at %.2f, %.2f)", seeker.state, *seeker.goal, pose.x, pose.y)
        if seeker.reached and self._state == "reached" and self.command == (0.0, 0.0):
            return None  # stopped there: the watchdog keeps it so
        return command


def main(argv: list[str] | None = None) -> int:
    """``skydeck run obstacle_avoider``."""
    return run_behaviour(ObstacleAvoider, argv, prog="obstacle_avoider", description=__doc__.splitlines()[0])
