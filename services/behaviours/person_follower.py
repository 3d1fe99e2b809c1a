"""Follow a walking person at a set distance, seen by the laser alone.

At the laser's height a person is two legs: two small clusters of returns a step apart, each
at most 25 cm across (walls and boxes make long ones) and standing out in front of what lies
behind it (a far wall seen at a slant breaks into small pieces that do not). The follower
splits each scan into clusters and pairs leg-sized ones less than 60 cm apart into people; a
leg on its own counts too, since one leg often hides the other. It takes the nearest candidate
that moved since the last scan (people walk; a box's corner that looks like a leg does not),
then follows the one nearest to where its person was last seen (in the odom frame, so the
robot's own motion does not confuse it): it turns towards the person and drives to keep
``distance`` metres from them (backing away from a person who walks at it), slower while the
person is off to the side. A person lost for more than a second makes it stop and turn the way
they were last seen.

    skydeck run person_follower --ros-args -p distance:=0.8
"""

from __future__ import annotations

import math

from services.behaviours.laser import Cluster, clusters
from services.behaviours.robot import Pose2D, RobotBehaviour, run_behaviour
from services.runtime import NodeSettings
from shared_models.sensor_msgs import LaserScan

__all__ = ["PersonFollower", "PersonFollowing", "find_people", "main"]

_LEG_MAX_WIDTH_M = 0.25
_STEP_M = 0.6  # two legs further apart than this are two people
_TRACK_GATE_M = 1.0  # a person seen further than this from the last sighting is someone else
_LOST_S = 1.0
_MOVED_M = 0.02  # a candidate this far from where one was in the last scan is walking
_TURN_GAIN = 2.5
_MAX_TURN = 1.8
_SPEED_GAIN = 3.0
_SEARCH_TURN = 0.6


def find_people(
    scan: LaserScan, max_range_m: float = 4.0, *, lone_legs: bool = True
) -> list[tuple[float, float]]:
    """People in the laser's frame (x, y): pairs of leg-sized clusters, then (``lone_legs``)
    single legs."""
    legs = [
        c for c in clusters(scan)
        if c.count >= 2 and c.width <= _LEG_MAX_WIDTH_M and c.stands_out and c.distance <= max_range_m
    ]  # fmt: skip
    people: list[tuple[float, float]] = []
    used: set[int] = set()
    pairs = sorted(
        ((math.hypot(a.x - b.x, a.y - b.y), i, j) for i, a in enumerate(legs) for j, b in enumerate(legs) if i < j),
    )
    for gap, i, j in pairs:
        if gap <= _STEP_M and i not in used and j not in used:
            used.update((i, j))
            people.append(_midpoint(legs[i], legs[j]))
    if lone_legs:
        people += [(leg.x, leg.y) for k, leg in enumerate(legs) if k not in used]
    return people


def _midpoint(a: Cluster, b: Cluster) -> tuple[float, float]:
    return (a.x + b.x) / 2.0, (a.y + b.y) / 2.0


class PersonFollower:
    """Person following as a controller: ``update(scan, pose, now_s)`` gives the command;
    ``target`` is the person followed, in the odom frame."""

    def __init__(self, distance: float = 0.8, speed: float = 0.3) -> None:
        self.distance = distance
        self.speed = speed
        self.target: tuple[float, float] | None = None
        self.seen_at_s = -math.inf
        self.state = "searching"
        self._scan: LaserScan | None = None
        self._seen: list[tuple[float, float]] = []
        self._before: list[tuple[float, float]] = []

    def update(self, scan: LaserScan, pose: Pose2D, now_s: float) -> tuple[float, float]:
        if scan is not self._scan:  # a new scan: who is where now, and where before
            self._scan = scan
            c, s = math.cos(pose.yaw), math.sin(pose.yaw)
            self._before = self._seen
            self._seen = [(pose.x + c * x - s * y, pose.y + s * x + c * y) for x, y in find_people(scan)]
        if self.target is not None:
            tx, ty = self.target
            near = [p for p in self._seen if math.hypot(p[0] - tx, p[1] - ty) <= _TRACK_GATE_M]
            choice = min(near, key=lambda p: math.hypot(p[0] - tx, p[1] - ty), default=None)
        else:
            # A new person must be walking: a box's corner can look like a leg, but stays put.
            walking = [p for p in self._seen if self._moved(p)]
            choice = min(walking, key=lambda p: pose.distance_to(*p), default=None)
        if choice is not None:
            self.target, self.seen_at_s = choice, now_s
        if self.target is None:
            self.state = "searching"
            return 0.0, _SEARCH_TURN
        bearing = pose.bearing_to(*self.target)
        if now_s - self.seen_at_s > _LOST_S:
            self.state = "lost"
            if now_s - self.seen_at_s > 10 * _LOST_S:
                self.target = None  # long gone: look for anyone
            return 0.0, math.copysign(_SEARCH_TURN, bearing)
        self.state = "following"
        gap = pose.distance_to(*self.target) - self.distance
        turn = max(-_MAX_TURN, min(_MAX_TURN, _TURN_GAIN * bearing))
        # Too near (the person walked at it): back away, as fast as it may drive forward.
        speed = max(-self.speed, min(self.speed, _SPEED_GAIN * gap)) * max(0.0, math.cos(bearing))
        return speed, turn

    def _moved(self, p: tuple[float, float]) -> bool:
        """Whether the nearest candidate of the scan before is a step's worth away (not the same
        spot, not someone else)."""
        nearest = min((math.dist(p, q) for q in self._before), default=math.inf)
        return _MOVED_M <= nearest <= _TRACK_GATE_M


class PersonFollowing(RobotBehaviour):
    """``person_follower``: a node around :class:`PersonFollower`."""

    def __init__(self, namespace: str = "/", settings: NodeSettings | None = None) -> None:
        super().__init__("person_follower", namespace, settings)
        self.declare_parameter("distance", 0.8)  # m, from the robot to the person
        self.declare_parameter("speed", 0.3)  # m/s at most
        self.follower = PersonFollower(self.get_parameter("distance").value, self.get_parameter("speed").value)
        self._state = ""

    def control(self) -> tuple[float, float] | None:
        scan, pose = self.sensors.scan, self.sensors.pose
        if scan is None or pose is None:
            return None
        follower = self.follower
        follower.distance = self.get_parameter("distance").value
        follower.speed = self.get_parameter("speed").value
        command = follower.update(scan, pose, self.get_clock().now().seconds())
        if follower.state != self._state:
            self._state = follower.state
            self.get_logger().info("%s", follower.state)
        return command


def main(argv: list[str] | None = None) -> int:
    """``skydeck run person_follower``."""
    return run_behaviour(PersonFollowing, argv, prog="person_follower", description=__doc__.splitlines()[0])
