"""The simulator node: the PyBullet world on topics and services (the seed's Gazebo + fake MAVROS).

    skydeck run sim --seed 1 --boxes 8 --speed max
    skydeck run sim --world robot --robots 2        # the robot world (sim_server.robot.node)

The drone world publishes (sim-time rates) ``/drone/pose`` 60 Hz, ``/clock`` with every pose,
``/simulator/boxes`` 10 Hz (latched), ``/drone/state`` 5 Hz, ``/simulator/world`` (latched) once
per build of the world (at start and at every reset: a new random id each time), and
``/simulator/camera`` (JPEG) and ``/simulator/camera/image_raw`` (rgb8) at ``--camera-rate``
(5 Hz of wall time by default) only while someone subscribes. Follows
``/drone/setpoint`` and, when no setpoint stream is active, ``/drone/cmd_vel``. Serves
``/simulator/reset``. Bad input is refused with a warning and never reaches the physics.
"""

from __future__ import annotations

import argparse
from typing import Any

from services.runtime import NodeSettings, spin
from services.runtime.settings import settings_from_flags
from shared_models.geometry_msgs import Point, Pose, PoseArray, PoseStamped, Quaternion, Twist
from shared_models.mavros_msgs import PositionTarget, State
from shared_models.std_msgs import Header
from sim_server.commands import InvalidCommand
from sim_server.limits import DEFAULT_BOXES, MAX_BOXES, PHYSICS_HZ
from sim_server.robot.limits import DEFAULT_OBSTACLES, MAX_OBSTACLES, MAX_ROBOTS
from sim_server.settings import (
    MAX_CAMERA_HEIGHT,
    MAX_CAMERA_RATE_HZ,
    MAX_CAMERA_WIDTH,
    MIN_CAMERA_RATE_HZ,
    MIN_CAMERA_SIDE,
    SimSettings,
)
from sim_server.world import Pose as BodyPose
from sim_server.world import World, WorldConfig
from sim_server.world_node import DEFAULT_PORT, WorldNode

__all__ = ["DEFAULT_PORT", "SimSettings", "SimulatorNode", "main"]

POSE_EVERY_STEPS = PHYSICS_HZ // 60  # 60 Hz sim time
BOXES_EVERY_STEPS = PHYSICS_HZ // 10  # 10 Hz
STATE_EVERY_STEPS = PHYSICS_HZ // 5  # 5 Hz


def _build_world(sim: SimSettings) -> World:
    return World(WorldConfig(seed=sim.seed, boxes=sim.boxes))


class SimulatorNode(WorldNode):
    """The drone world as a node."""

    PUBLISH_EVERY_STEPS = POSE_EVERY_STEPS
    WORLD_NAME = "drone"

    def __init__(
        self, sim: SimSettings | None = None, settings: NodeSettings | None = None
    ) -> None:
        super().__init__(sim or SimSettings(), settings, _build_world)
        self.world: World
        self.pose_publisher = self.create_publisher(PoseStamped, "/drone/pose", 10)
        self.state_publisher = self.create_publisher(State, "/drone/state", 10)
        self.boxes_publisher = self.create_publisher(
            PoseArray, "/simulator/boxes", 10, latched=True
        )
        self.create_subscription(PositionTarget, "/drone/setpoint", self.on_setpoint, 10)
        self.create_subscription(Twist, "/drone/cmd_vel", self.on_cmd_vel, 10)
        self._announce(f"{self.sim.boxes} boxes")

    def _count_parameters(self) -> dict[str, tuple[int, int, str]]:
        return {"boxes": (self.sim.boxes, MAX_BOXES, "number of falling boxes")}

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
        return {"world": "drone", "boxes": self.sim.boxes}

    def _render_camera(self, width: int, height: int) -> bytes:
        from sim_server.camera import chase_view, render_rgb

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
        self.clock_publisher.publish_built(header.stamp.model_copy)
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


def main(argv: list[str] | None = None) -> int:
    """``skydeck run sim [--world drone|robot] [--seed N] [--speed F|max] [--boxes K]
    [--robots N] [--obstacles K] [--camera-width W] [--camera-height H] [--camera-rate HZ]``."""
    parser = argparse.ArgumentParser(
        prog="skydeck run sim", description="The PyBullet simulator: the drone world or the robot world."
    )
    parser.add_argument(
        "--world",
        help="drone (default): the workshop's drone and boxes; robot: the Neato room; soccer: the Neato room with a ball",
    )
    parser.add_argument("--seed", help="random seed; the same seed gives the same world")
    parser.add_argument("--speed", help="times real time, or 'max' (default 1)")
    parser.add_argument("--boxes", help=f"drone world: number of boxes, 0-{MAX_BOXES} (default {DEFAULT_BOXES})")
    parser.add_argument("--robots", help=f"robot world: number of robots, 1-{MAX_ROBOTS} (default 1)")
    parser.add_argument(
        "--obstacles", help=f"robot world: number of box obstacles, 0-{MAX_OBSTACLES} (default {DEFAULT_OBSTACLES})"
    )
    parser.add_argument("--camera-width", help=f"camera image width, {MIN_CAMERA_SIDE}-{MAX_CAMERA_WIDTH} pixels (default 320)")
    parser.add_argument("--camera-height", help=f"camera image height, {MIN_CAMERA_SIDE}-{MAX_CAMERA_HEIGHT} pixels (default 240)")
    parser.add_argument(
        "--camera-rate",
        help=f"camera frames a second while watched, {MIN_CAMERA_RATE_HZ:g}-{MAX_CAMERA_RATE_HZ:g} (default 5)",
    )
    sim = settings_from_flags(parser, SimSettings, argv)
    if sim.world in ("robot", "soccer"):
        from sim_server.robot.node import RobotSimNode
        from sim_server.soccer.node import SoccerSimNode

        if "boxes" in sim.model_fields_set:
            parser.error("--boxes (SKYDECK_SIM_BOXES) is the drone world's: the robot world has --obstacles")
        spin(SoccerSimNode(sim) if sim.world == "soccer" else RobotSimNode(sim))
    else:
        spin(SimulatorNode(sim))
    return 0
