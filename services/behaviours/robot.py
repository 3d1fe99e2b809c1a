"""What every behaviour of the robot world shares: a node that reads the Neato's ``scan``,
``odom`` and ``bump``, and drives it on ``cmd_vel``, in the robot's namespace.

    class Spin(RobotBehaviour):
        def __init__(self, namespace="/", settings=None):
            super().__init__("spin", namespace, settings)
            self.declare_parameter("turn_rate", 0.5)

        def control(self):
            return 0.0, self.get_parameter("turn_rate").value   # (forward m/s, turn rad/s)

``control()`` runs RATE_HZ times a second (on sim time with ``--use-sim-time``) and returns the
command to send, or None to send nothing this time. ``run_behaviour`` is every behaviour's
``main``: ``skydeck run NAME [--namespace /robot1] [--ros-args -p NAME:=VALUE ...]``;
``--namespace /robot1`` is ``--ros-args -r __ns:=/robot1``: the node is ``/robot1/NAME`` and
drives ``/robot1/cmd_vel``.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from dataclasses import dataclass, field

from services.runtime import Node, NodeSettings, spin
from services.runtime.ros_args import parse_ros_args, set_process_ros_arguments, split_ros_args
from shared_models.errors import SkydeckError
from shared_models.geometry_msgs import Twist, Vector3
from shared_models.nav_msgs import Odometry
from shared_models.neato2_interfaces import Bump
from shared_models.sensor_msgs import LaserScan

__all__ = ["BehaviourError", "Pose2D", "RobotBehaviour", "Sensors", "run_behaviour"]


class BehaviourError(SkydeckError):
    """A behaviour that cannot start as asked (the message says why)."""


@dataclass(frozen=True, slots=True)
class Pose2D:
    """A pose on the floor: x, y (m) and heading (rad), in the odom frame."""

    x: float
    y: float
    yaw: float

    def distance_to(self, x: float, y: float) -> float:
        return math.hypot(x - self.x, y - self.y)

    def bearing_to(self, x: float, y: float) -> float:
        """The angle (rad, counter-clockwise, within +-pi) from the heading to the point (x, y)."""
        return math.remainder(math.atan2(y - self.y, x - self.x) - self.yaw, math.tau)


@dataclass
class Sensors:
    """The latest of each sensor (None until the first message)."""

    scan: LaserScan | None = None
    pose: Pose2D | None = None
    bump: Bump | None = None
    bumps: int = field(default=0)
    """How many bump messages reported a press so far."""

    def on_scan(self, msg: LaserScan) -> None:
        self.scan = msg

    def on_odom(self, msg: Odometry) -> None:
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        self.pose = Pose2D(p.x, p.y, yaw)

    def on_bump(self, msg: Bump) -> None:
        self.bump = msg
        if self.bumped:
            self.bumps += 1

    @property
    def bumped(self) -> bool:
        """Whether any bumper switch is pressed now."""
        b = self.bump
        return b is not None and bool(b.left_front or b.left_side or b.right_front or b.right_side)


class RobotBehaviour(Node):
    """A node that senses and drives one robot; subclasses implement :meth:`control`."""

    RATE_HZ = 20.0

    def __init__(self, node_name: str, namespace: str = "/", settings: NodeSettings | None = None) -> None:
        # The node itself goes in the namespace, as rclpy's Node(name, namespace=...) and
        # `--ros-args -r __ns:=/robot1` put it (a later __ns wins): /robot1/wall_follower, its
        # relative names (cmd_vel, scan, ...) resolved there.
        super().__init__(node_name, namespace=namespace, settings=settings)
        self.sensors = Sensors()
        self.cmd_vel = self.create_publisher(Twist, "cmd_vel", 10)
        self.create_subscription(LaserScan, "scan", self.sensors.on_scan, 1)
        self.create_subscription(Odometry, "odom", self.sensors.on_odom, 1)
        self.create_subscription(Bump, "bump", self.sensors.on_bump, 10)
        self.create_timer(1.0 / self.RATE_HZ, self._tick)
        self.command = (0.0, 0.0)

    def control(self) -> tuple[float, float] | None:
        """The command to send now: (forward m/s, counter-clockwise rad/s), or None for none."""
        raise NotImplementedError

    def drive(self, linear: float, angular: float) -> None:
        """Send one command on cmd_vel."""
        self.command = (linear, angular)
        self.cmd_vel.publish(Twist(linear=Vector3(x=linear), angular=Vector3(z=angular)))

    def _tick(self) -> None:
        command = self.control()
        if command is not None:
            self.drive(*command)


def run_behaviour(
    factory: Callable[[str], RobotBehaviour], argv: list[str] | None, *, prog: str, description: str
) -> int:
    """A behaviour's ``main``: ``--namespace NS`` picks the robot, ``--ros-args -p`` its parameters."""
    parser = argparse.ArgumentParser(prog=f"skydeck run {prog}", description=description)
    parser.add_argument(
        "--namespace",
        default="/",
        help="the robot's namespace, e.g. /robot1 with --robots 2 (default: /); as --ros-args -r __ns:=/robot1",
    )
    node_argv, ros_argv = split_ros_args(list(argv or []))
    args = parser.parse_args(node_argv)
    try:
        if ros_argv:  # called directly, not through `skydeck run` (which has read them)
            set_process_ros_arguments(parse_ros_args(ros_argv))
        node = factory(args.namespace)
    except SkydeckError as error:
        parser.error(str(error))
    spin(node)
    return 0
