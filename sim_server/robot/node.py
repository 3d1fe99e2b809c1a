"""The robot world as a node, with the topics a Neato's ROS 2 driver has.

    skydeck run sim --world robot [--robots N] [--obstacles K] [--seed S] [--speed F|max]

Per robot, under its namespace (none with one robot; ``/robot1``, ``/robot2``... with more; a
class's ``/NAME`` per student, ``SKYDECK_SIM_STUDENTS=alice,bob`` as ``skydeck class`` sets it):
follows ``cmd_vel`` (geometry_msgs/Twist, body frame; 0.5 s without one stops it), publishes
``odom`` (nav_msgs/Odometry, 30 Hz), ``bump`` (neato2_interfaces/Bump, 30 Hz) and ``scan``
(sensor_msgs/LaserScan, 5 Hz). For everyone: ``/tf`` (odom -> base_link of each robot, 30 Hz),
``/tf_static`` (map -> odom, base_link -> base_laser_link; latched), ``/clock`` (30 Hz), the
truth for judges and the dashboard: ``/simulator/robots`` and ``/simulator/people``
(geometry_msgs/PoseArray in ``map``, 10 Hz) and ``/simulator/obstacles``
(visualization_msgs/MarkerArray: walls and boxes, latched), ``/simulator/world`` (latched),
``/simulator/camera`` (robot 1's forward view, while watched) and ``/simulator/reset``.
Frames carry the namespace as a prefix with several robots (``robot1/odom``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial
from typing import Any

from services.runtime import NodeSettings, Publisher
from shared_models.builtin_interfaces import Time, split_seconds
from shared_models.geometry_msgs import (
    Point,
    Pose,
    PoseArray,
    Quaternion,
    Transform,
    TransformStamped,
    Twist,
    Vector3,
)
from shared_models.nav_msgs import Odometry
from shared_models.neato2_interfaces import Bump
from shared_models.sensor_msgs import LaserScan
from shared_models.std_msgs import ColorRGBA, Header
from shared_models.tf2_msgs import TFMessage
from shared_models.visualization_msgs import Marker, MarkerArray
from sim_server.camera import View, render_rgb
from sim_server.checks import InvalidCommand
from sim_server.robot.limits import (
    LASER_HEIGHT_M,
    OBSTACLE_HEIGHT_M,
    ODOM_EVERY_STEPS,
    PHYSICS_DT_S,
    RANGE_MAX_M,
    RANGE_MIN_M,
    ROOM_HALF_SIZE_M,
    SCAN_ANGLE_INCREMENT,
    SCAN_BEAMS,
    SCAN_EVERY_STEPS,
    TRUTH_EVERY_STEPS,
    WALL_HEIGHT_M,
    WALL_THICKNESS_M,
)
from sim_server.robot.settings import RobotSettings
from sim_server.robot.world import Bump as WorldBump
from sim_server.robot.world import RobotWorld, RobotWorldConfig
from sim_server.world_node import WorldNode

__all__ = ["RobotSimNode", "robot_namespaces"]

_SCAN_PERIOD_S = SCAN_EVERY_STEPS * PHYSICS_DT_S
# Odometry's covariance: diagonal, small; what a Neato's driver would claim.
_POSE_COVARIANCE = [1e-3 if i in (0, 7, 35) else (1e6 if i in (14, 21, 28) else 0.0) for i in range(36)]
_TWIST_COVARIANCE = [1e-3 if i in (0, 35) else (1e6 if i in (7, 14, 21, 28) else 0.0) for i in range(36)]
_WALL_COLOUR = ColorRGBA(r=0.92, g=0.92, b=0.95, a=1.0)
_OBSTACLE_COLOUR = ColorRGBA(r=0.55, g=0.42, b=0.30, a=1.0)


def robot_namespaces(count: int) -> list[str]:
    """Where each robot's topics live: ``["/"]`` for one robot, else ``/robot1``, ``/robot2``..."""
    return ["/"] if count == 1 else [f"/robot{i + 1}" for i in range(count)]


def _yaw_quaternion(yaw: float) -> Quaternion:
    return Quaternion(x=0.0, y=0.0, z=math.sin(yaw / 2.0), w=math.cos(yaw / 2.0))


class _RobotTopics:
    """One robot's names and publishers."""

    def __init__(self, node: RobotSimNode, index: int, namespace: str) -> None:
        prefix = "" if namespace == "/" else namespace.strip("/") + "/"
        base = "" if namespace == "/" else namespace
        self.index = index
        self.odom_frame = f"{prefix}odom"
        self.base_frame = f"{prefix}base_link"
        self.laser_frame = f"{prefix}base_laser_link"
        self.odom = node.create_publisher(Odometry, f"{base}/odom", 10)
        self.scan = node.create_publisher(LaserScan, f"{base}/scan", 5)
        self.bump = node.create_publisher(Bump, f"{base}/bump", 10)
        node.create_subscription(Twist, f"{base}/cmd_vel", self.on_cmd_vel, 10)
        self._node = node

    def on_cmd_vel(self, msg: Twist) -> None:
        try:
            self._node.world.set_cmd_vel(self.index, msg.linear.x, msg.angular.z)
        except InvalidCommand as error:  # only from Python callers: JSON carries no NaN
            self._node.warn("cmd_vel", f"refused cmd_vel: {error}; the robot stops")


def _build_world(sim: RobotSettings) -> RobotWorld:
    return RobotWorld(
        RobotWorldConfig(seed=sim.seed, robots=sim.robots, obstacles=sim.obstacles, students=sim.student_names)
    )


class RobotSimNode(WorldNode[RobotSettings]):
    """The robot world as a node; ``world`` is its :class:`RobotWorld`."""

    PUBLISH_EVERY_STEPS = ODOM_EVERY_STEPS  # 30 Hz: odom, bump, tf and clock
    WORLD_NAME = "robot"

    def __init__(
        self,
        sim: RobotSettings | None = None,
        settings: NodeSettings | None = None,
        build: Callable[[RobotSettings], RobotWorld] = _build_world,
    ) -> None:
        super().__init__(sim or RobotSettings(), settings, build)
        self.world: RobotWorld
        world = self.world
        students = world.config.students
        self.namespaces = [f"/{name}" for name in students] if students else robot_namespaces(world.robot_count)
        self.robots = [_RobotTopics(self, i, ns) for i, ns in enumerate(self.namespaces)]
        self.tf_publisher = self.create_publisher(TFMessage, "/tf", 100)
        self.tf_static_publisher = self.create_publisher(TFMessage, "/tf_static", 1, latched=True)
        self.truth_publisher = self.create_publisher(PoseArray, "/simulator/robots", 10)
        self.people_publisher = self.create_publisher(PoseArray, "/simulator/people", 10)
        self.obstacles_publisher: Publisher[MarkerArray] = self.create_publisher(
            MarkerArray, "/simulator/obstacles", 1, latched=True
        )
        self._announce(
            f"{world.robot_count} robot{'s' if world.robot_count > 1 else ''}, "
            f"{len(world.obstacles)} obstacles"
        )
        self._publish_build()

    # -- the world's hooks --------------------------------------------------------------------

    def _reset_world(self) -> str:
        self.world.reset()
        return "robots at their starts, odometry zeroed, the person at the start of the walk"

    def _world_fields(self) -> dict[str, Any]:
        return {"boxes": len(self.world.obstacles), "namespaces": self.namespaces}

    def _render_camera(self, width: int, height: int) -> bytes:
        x, y, yaw = self.world.robot_pose(0)
        c, s = math.cos(yaw), math.sin(yaw)
        eye = (x + 0.1 * c, y + 0.1 * s, LASER_HEIGHT_M + 0.1)
        target = (x + 2.0 * c, y + 2.0 * s, LASER_HEIGHT_M)
        return render_rgb(self.world.client, View(eye, target, near_m=0.05, far_m=12.0), width, height)

    def _publish_tick(self, steps: int) -> None:
        # The simulator's hot path at --speed max. The world is read now; each message is made
        # only if someone reads its topic (publish_built), from plain dicts (a third cheaper than
        # nested constructors). Unread topics are the common case at speed max, where building
        # them took about a quarter of the node's time (docs/performance.md).
        world = self.world
        sec, nanosec = split_seconds(world.time_s)
        stamp = {"sec": sec, "nanosec": nanosec}
        scanning = steps % SCAN_EVERY_STEPS == 0
        transforms = []
        for robot in self.robots:
            odometry = world.odometry(robot.index)
            position = {"x": odometry.x, "y": odometry.y, "z": 0.0}
            orientation = _yaw_orientation(odometry.yaw)
            transforms.append({
                "header": {"stamp": stamp, "frame_id": robot.odom_frame},
                "child_frame_id": robot.base_frame,
                "transform": {"translation": position, "rotation": orientation},
            })  # fmt: skip
            robot.odom.publish_built(
                partial(_odometry, stamp, robot, position, orientation, odometry.linear, odometry.angular)
            )
            bump = world.bump(robot.index)
            robot.bump.publish_built(partial(_bump_message, bump))
            if scanning:
                # Rays are cast only for a scan someone reads: a class's idle robots cost none
                # (docs/performance.md). An unread scan asked for later (GET) is cast then, from
                # this tick's pose.
                cast = partial(world.scan_from, *world.robot_pose(robot.index))
                robot.scan.publish_built(partial(_laser_scan, stamp, robot.laser_frame, cast))
        self.tf_publisher.publish_built(lambda: TFMessage.model_validate({"transforms": transforms}))
        if steps % TRUTH_EVERY_STEPS == 0:
            header = {"stamp": stamp, "frame_id": "map"}
            robots = [_pose(*world.robot_pose(r.index)) for r in self.robots]
            self.truth_publisher.publish_built(lambda: PoseArray.model_validate({"header": header, "poses": robots}))
            person = [_pose(*world.person_pose())]
            self.people_publisher.publish_built(
                lambda: PoseArray.model_validate({"header": header, "poses": person})
            )

    def _publish_build(self) -> None:
        """The transforms that never move, and the room's walls and boxes (once per build)."""
        self.tf_static_publisher.publish(TFMessage(transforms=self._static_transforms(self.header().stamp)))
        self.obstacles_publisher.publish(MarkerArray(markers=self._room_markers()))

    def _static_transforms(self, stamp: Time) -> list[TransformStamped]:
        """Each robot's map -> odom and base_link -> base_laser_link (a world with more sensors adds theirs)."""
        transforms = []
        for robot in self.robots:
            sx, sy, syaw = self.world.robot_start(robot.index)
            transforms.append(
                TransformStamped(
                    header=Header(stamp=stamp, frame_id="map"),
                    child_frame_id=robot.odom_frame,
                    transform=Transform(translation=Vector3(x=sx, y=sy), rotation=_yaw_quaternion(syaw)),
                )
            )
            transforms.append(
                TransformStamped(
                    header=Header(stamp=stamp, frame_id=robot.base_frame),
                    child_frame_id=robot.laser_frame,
                    transform=Transform(translation=Vector3(z=LASER_HEIGHT_M), rotation=_yaw_quaternion(0.0)),
                )
            )
        return transforms

    def _room_markers(self) -> list[Marker]:
        header = self.header()
        markers = []
        half, thick = ROOM_HALF_SIZE_M, WALL_THICKNESS_M
        length = 2.0 * (half + thick)
        walls = ((half + thick / 2, 0.0, thick, length), (-half - thick / 2, 0.0, thick, length),
                 (0.0, half + thick / 2, length, thick), (0.0, -half - thick / 2, length, thick))  # fmt: skip
        for i, (x, y, sx, sy) in enumerate(walls):
            markers.append(
                Marker(
                    header=header.model_copy(), ns="walls", id=i, type=Marker.CUBE,
                    pose=Pose(position=Point(x=x, y=y, z=WALL_HEIGHT_M / 2), orientation=_yaw_quaternion(0.0)),
                    scale=Vector3(x=sx, y=sy, z=WALL_HEIGHT_M), color=_WALL_COLOUR.model_copy(),
                )  # fmt: skip
            )
        for i, box in enumerate(self.world.obstacles):
            markers.append(
                Marker(
                    header=header.model_copy(), ns="obstacles", id=i, type=Marker.CUBE,
                    pose=Pose(position=Point(x=box.x, y=box.y, z=OBSTACLE_HEIGHT_M / 2), orientation=_yaw_quaternion(box.yaw)),
                    scale=Vector3(x=box.size, y=box.size, z=OBSTACLE_HEIGHT_M), color=_OBSTACLE_COLOUR.model_copy(),
                )  # fmt: skip
            )
        return markers


def _pose(x: float, y: float, yaw: float) -> dict[str, dict[str, float]]:
    return {"position": {"x": x, "y": y, "z": 0.0}, "orientation": _yaw_orientation(yaw)}


def _yaw_orientation(yaw: float) -> dict[str, float]:
    return {"x": 0.0, "y": 0.0, "z": math.sin(yaw / 2.0), "w": math.cos(yaw / 2.0)}


# The messages of a tick, made from what the world said then (when someone reads them).


def _odometry(
    stamp: dict[str, int], robot: _RobotTopics, position: dict[str, float], orientation: dict[str, float],
    linear: float, angular: float,
) -> Odometry:  # fmt: skip
    return Odometry.model_validate({
        "header": {"stamp": stamp, "frame_id": robot.odom_frame},
        "child_frame_id": robot.base_frame,
        "pose": {"pose": {"position": position, "orientation": orientation}, "covariance": _POSE_COVARIANCE},
        "twist": {
            "twist": {"linear": {"x": linear, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": angular}},
            "covariance": _TWIST_COVARIANCE,
        },
    })  # fmt: skip


def _bump_message(bump: WorldBump) -> Bump:
    return Bump(
        left_front=int(bump.left_front),
        left_side=int(bump.left_side),
        right_front=int(bump.right_front),
        right_side=int(bump.right_side),
    )


def _laser_scan(stamp: dict[str, int], frame_id: str, cast: Callable[[], list[float]]) -> LaserScan:
    return LaserScan.model_validate({
        "header": {"stamp": stamp, "frame_id": frame_id},
        "angle_min": 0.0,
        "angle_max": (SCAN_BEAMS - 1) * SCAN_ANGLE_INCREMENT,
        "angle_increment": SCAN_ANGLE_INCREMENT,
        "time_increment": 0.0,
        "scan_time": _SCAN_PERIOD_S,
        "range_min": RANGE_MIN_M,
        "range_max": RANGE_MAX_M,
        "ranges": cast(),
    })  # fmt: skip
