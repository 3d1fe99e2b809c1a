"""A robot for the 3D view's browser tests, as a real node: the robot world's topics and frames.

It drives a known circle in an 8 m x 8 m room (walls at x, y = +-4 m in ``map``) and publishes
what the robot world does: ``/odom`` (odom -> base_link, 20 Hz), ``/tf`` (the same transform),
``/tf_static`` (map -> odom, where odometry started, and base_link -> base_laser_link; latched),
``/scan`` (360 beams, ``ranges[0]`` straight ahead, counter-clockwise, 5 Hz, 0.0 where no wall
is within 5 m), and the simulator's ``/simulator/obstacles`` (the walls as CUBE markers in
``map``, latched) and ``/simulator/people`` (one person standing still, which this scan does
not see). Poses and ranges are pure functions of the stamp (``pose_at``, ``scan_at``), so a test
can tell where every drawn point must be. Run it with ``skydeck run tests/web_ui/robot_stand_in.py``.
"""

from __future__ import annotations

import math
import time

from services.runtime import Node, spin
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import (
    Point,
    Pose,
    PoseArray,
    Quaternion,
    Transform,
    TransformStamped,
    Vector3,
)
from shared_models.nav_msgs import Odometry
from shared_models.sensor_msgs import LaserScan
from shared_models.std_msgs import ColorRGBA, Header
from shared_models.tf2_msgs import TFMessage
from shared_models.visualization_msgs import Marker, MarkerArray

WALL_M = 4.0
WALL_HEIGHT_M = 0.5
ODOM_IN_MAP = (0.3, -0.2, 0.25)  # map -> odom: x, y, yaw
LASER_OFFSET = (0.1, 0.0, 0.1)  # base_link -> base_laser_link
PERSON = (-2.0, 2.5, math.pi)  # in map: x, y, yaw
CIRCLE_CENTRE = (1.0, -0.5)
CIRCLE_RADIUS_M = 0.5
TURN_RATE = 0.3  # rad/s around the circle: 0.15 m/s
BEAMS = 360
RANGE_MIN_M = 0.2
RANGE_MAX_M = 5.0


def pose_at(t: float) -> tuple[float, float, float]:
    """(x, y, yaw) of base_link in odom at time ``t`` (s): driving counter-clockwise on a circle."""
    angle = TURN_RATE * t
    x = CIRCLE_CENTRE[0] + CIRCLE_RADIUS_M * math.cos(angle)
    y = CIRCLE_CENTRE[1] + CIRCLE_RADIUS_M * math.sin(angle)
    return x, y, angle + math.pi / 2


def odom_to_map(x: float, y: float, yaw: float = 0.0) -> tuple[float, float, float]:
    """A pose (x, y, yaw) in odom, in map."""
    ox, oy, oyaw = ODOM_IN_MAP
    c, s = math.cos(oyaw), math.sin(oyaw)
    return ox + c * x - s * y, oy + s * x + c * y, oyaw + yaw


def laser_at(t: float) -> tuple[float, float, float]:
    """(x, y, yaw) of base_laser_link in map at time ``t``."""
    x, y, yaw = odom_to_map(*pose_at(t))
    return x + LASER_OFFSET[0] * math.cos(yaw), y + LASER_OFFSET[0] * math.sin(yaw), yaw


def range_to_walls(x: float, y: float, heading: float) -> float:
    """Distance from (x, y) along ``heading`` to the room's walls."""
    dx, dy = math.cos(heading), math.sin(heading)
    hits = []
    if abs(dx) > 1e-12:
        hits.append((math.copysign(WALL_M, dx) - x) / dx)
    if abs(dy) > 1e-12:
        hits.append((math.copysign(WALL_M, dy) - y) / dy)
    return min(h for h in hits if h > 0)


def scan_at(t: float) -> list[float]:
    """The 360 ranges at time ``t``; 0.0 beyond RANGE_MAX_M (the Neato's "no return")."""
    x, y, yaw = laser_at(t)
    ranges = []
    for i in range(BEAMS):
        r = range_to_walls(x, y, yaw + i * 2 * math.pi / BEAMS)
        ranges.append(r if RANGE_MIN_M <= r <= RANGE_MAX_M else 0.0)
    return ranges


# The walls' centres and sizes (x, y, length along x, along y): 0.1 m thick, just outside +-4 m.
WALLS = [
    (WALL_M + 0.05, 0.0, 0.1, 2 * WALL_M + 0.2),
    (-WALL_M - 0.05, 0.0, 0.1, 2 * WALL_M + 0.2),
    (0.0, WALL_M + 0.05, 2 * WALL_M + 0.2, 0.1),
    (0.0, -WALL_M - 0.05, 2 * WALL_M + 0.2, 0.1),
]


def _wall(index: int, x: float, y: float, size_x: float, size_y: float) -> Marker:
    return Marker(
        header=Header(frame_id="map"),
        ns="walls",
        id=index,
        type=Marker.CUBE,
        pose=Pose(position=Point(x=x, y=y, z=WALL_HEIGHT_M / 2)),
        scale=Vector3(x=size_x, y=size_y, z=WALL_HEIGHT_M),
        color=ColorRGBA(r=0.92, g=0.92, b=0.95, a=1.0),
    )


def _stamp(t: float) -> Time:
    sec = math.floor(t)
    return Time(sec=sec, nanosec=int((t - sec) * 1e9))


def _yaw(yaw: float) -> Quaternion:
    return Quaternion(z=math.sin(yaw / 2), w=math.cos(yaw / 2))


class RobotStandIn(Node):
    """Publishes the robot world's topics and frames for a robot on a circle."""

    def __init__(self) -> None:
        super().__init__("robot_stand_in")
        self.odom = self.create_publisher(Odometry, "/odom", 10)
        self.tf = self.create_publisher(TFMessage, "/tf", 100)
        self.tf_static = self.create_publisher(TFMessage, "/tf_static", 10, latched=True)
        self.scan = self.create_publisher(LaserScan, "/scan", 10)
        self.obstacles = self.create_publisher(MarkerArray, "/simulator/obstacles", 1, latched=True)
        self.people = self.create_publisher(PoseArray, "/simulator/people", 10)
        self.create_timer(0.05, self.publish_pose)
        self.create_timer(0.2, self.publish_scan)
        self.create_timer(1.0, self.publish_static)  # latched; again each second for late readers
        self.publish_static()

    def publish_static(self) -> None:
        stamp = _stamp(time.time())
        odom = TransformStamped(
            header=Header(stamp=stamp, frame_id="map"),
            child_frame_id="odom",
            transform=Transform(
                translation=Vector3(x=ODOM_IN_MAP[0], y=ODOM_IN_MAP[1]),
                rotation=_yaw(ODOM_IN_MAP[2]),
            ),
        )
        laser = TransformStamped(
            header=Header(stamp=stamp, frame_id="base_link"),
            child_frame_id="base_laser_link",
            transform=Transform(
                translation=Vector3(x=LASER_OFFSET[0], y=LASER_OFFSET[1], z=LASER_OFFSET[2])
            ),
        )
        self.tf_static.publish(TFMessage(transforms=[odom, laser]))
        self.obstacles.publish(MarkerArray(markers=[_wall(i, *w) for i, w in enumerate(WALLS)]))
        person = Pose(position=Point(x=PERSON[0], y=PERSON[1]), orientation=_yaw(PERSON[2]))
        self.people.publish(PoseArray(header=Header(stamp=stamp, frame_id="map"), poses=[person]))

    def publish_pose(self) -> None:
        t = time.time()
        x, y, yaw = pose_at(t)
        header = Header(stamp=_stamp(t), frame_id="odom")
        odom = Odometry(header=header, child_frame_id="base_link")
        odom.pose.pose.position.x = x
        odom.pose.pose.position.y = y
        odom.pose.pose.orientation = _yaw(yaw)
        self.odom.publish(odom)
        transform = Transform(translation=Vector3(x=x, y=y), rotation=_yaw(yaw))
        self.tf.publish(
            TFMessage(
                transforms=[
                    TransformStamped(header=header, child_frame_id="base_link", transform=transform)
                ]
            )
        )

    def publish_scan(self) -> None:
        t = time.time()
        self.scan.publish(
            LaserScan(
                header=Header(stamp=_stamp(t), frame_id="base_laser_link"),
                angle_min=0.0,
                angle_max=2 * math.pi * (BEAMS - 1) / BEAMS,
                angle_increment=2 * math.pi / BEAMS,
                scan_time=0.2,
                range_min=RANGE_MIN_M,
                range_max=RANGE_MAX_M,
                ranges=scan_at(t),
            )
        )


if __name__ == "__main__":
    spin(RobotStandIn())
