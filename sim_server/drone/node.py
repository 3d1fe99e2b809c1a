"""The drone world as a node: the PyBullet drone and boxes on topics and services (the seed's
Gazebo + fake MAVROS).

    skydeck run sim --seed 1 --boxes 8 --speed max

It publishes (sim-time rates) ``/drone/pose`` 60 Hz, ``/clock`` with every pose (``WorldNode``),
``/simulator/boxes`` 10 Hz (latched), ``/drone/state`` 5 Hz, ``/simulator/world`` (latched) once
per build of the world (at start and at every reset: a new random id each time), and
``/simulator/camera`` (JPEG) and ``/simulator/camera/image_raw`` (rgb8) at ``--camera-rate``
(5 Hz of wall time by default) only while someone subscribes. Follows
``/drone/setpoint`` and, when no setpoint stream is active, ``/drone/cmd_vel``. Serves
``/simulator/reset``. Bad input is refused with a warning and never reaches the physics.
"""

from __future__ import annotations

from typing import Any

from services.runtime import NodeSettings
from shared_models.geometry_msgs import Point, Pose, PoseArray, PoseStamped, Quaternion, Twist
from shared_models.mavros_msgs import PositionTarget, State
from shared_models.std_msgs import Header
from sim_server.camera import render_rgb
from sim_server.checks import InvalidCommand
from sim_server.drone.camera import chase_view
from sim_server.drone.limits import PHYSICS_HZ
from sim_server.drone.settings import DroneSettings
from sim_server.drone.world import World, WorldConfig
from sim_server.geometry import Pose as BodyPose
from sim_server.world_node import WorldNode

__all__ = ["DroneSimNode"]

POSE_EVERY_STEPS = PHYSICS_HZ // 60  # 60 Hz sim time
BOXES_EVERY_STEPS = PHYSICS_HZ // 10  # 10 Hz
STATE_EVERY_STEPS = PHYSICS_HZ // 5  # 5 Hz


def _build_world(sim: DroneSettings) -> World:
    return World(WorldConfig(seed=sim.seed, boxes=sim.boxes))


class DroneSimNode(WorldNode[DroneSettings]):
    """The drone world as a node."""

    PUBLISH_EVERY_STEPS = POSE_EVERY_STEPS
    WORLD_NAME = "drone"

    def __init__(self, sim: DroneSettings | None = None, settings: NodeSettings | None = None) -> None:
        super().__init__(sim or DroneSettings(), settings, _build_world)
        self.world: World
        self.pose_publisher = self.create_publisher(PoseStamped, "/drone/pose", 10)
        self.state_publisher = self.create_publisher(State, "/drone/state", 10)
        self.boxes_publisher = self.create_publisher(
            PoseArray, "/simulator/boxes", 10, latched=True
        )
        self.create_subscription(PositionTarget, "/drone/setpoint", self.on_setpoint, 10)
        self.create_subscription(Twist, "/drone/cmd_vel", self.on_cmd_vel, 10)
        self._announce(f"{self.sim.boxes} boxes")

    # -- inputs -------------------------------------------------------------------------------

    def on_setpoint(self, msg: PositionTarget) -> None:
        p = msg.position
        try:
            self.world.set_setpoint(p.x, p.y, p.z, yaw=msg.yaw)
        except InvalidCommand as error:
            self.warn("setpoint", f"refused setpoint: {error}")

    def on_cmd_vel(self, msg: Twist) -> None:
        try:
            self.world.set_cmd_vel(msg.linear.x, msg.linear.y, msg.linear.z, msg.angular.z)
        except InvalidCommand as error:
            self.warn("cmd_vel", f"refused cmd_vel: {error}")

    # -- the world's hooks --------------------------------------------------------------------

    def _reset_world(self) -> str:
        self.world.reset()
        return f"drone at the start, {self.sim.boxes} new boxes dropped"

    def _publish_build(self) -> None:
        self.boxes_publisher.publish(_boxes_message(self.header(), self.world.boxes_poses()))

    def _world_fields(self) -> dict[str, Any]:
        return {"boxes": self.sim.boxes}

    def _render_camera(self, width: int, height: int) -> bytes:
        return render_rgb(self.world.client, chase_view(self.world), width, height)

    def _publish_tick(self, steps: int) -> None:
        # The world is read now; the messages of topics nobody reads are made only if asked for
        # (publish_built), as in the robot world's node.
        header = self.header()
        (x, y, z), (qx, qy, qz, qw) = self.world.drone_pose()
        self.pose_publisher.publish_built(
            lambda: PoseStamped(
                header=header,
                pose=Pose(position=Point(x=x, y=y, z=z), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw)),
            )
        )
        if steps % BOXES_EVERY_STEPS == 0:
            boxes = self.world.boxes_poses()
            self.boxes_publisher.publish_built(lambda: _boxes_message(header.model_copy(), boxes))
        if steps % STATE_EVERY_STEPS == 0:
            state = self.world.drone_state()
            self.state_publisher.publish_built(
                lambda: State(
                    header=header.model_copy(),
                    connected=True,
                    armed=state.armed,
                    guided=state.mode.value == "OFFBOARD",
                    manual_input=False,
                    mode=state.mode.value,
                    system_status=4 if state.armed else 3,  # MAV_STATE_ACTIVE / STANDBY
                )
            )


def _boxes_message(header: Header, boxes: list[BodyPose]) -> PoseArray:
    poses = [
        Pose(position=Point(x=x, y=y, z=z), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw))
        for (x, y, z), (qx, qy, qz, qw) in boxes
    ]
    return PoseArray(header=header, poses=poses)
