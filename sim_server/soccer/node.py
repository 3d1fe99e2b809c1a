"""The soccer room as a node: the robot world's node (every topic of ``sim_server.robot.node``)
with a ball and a forward camera on every robot.

    skydeck launch soccer                  # or: skydeck run sim --world soccer [--robots N] ...

Adds, per robot under its namespace, ``camera/image_raw`` (sensor_msgs/Image, rgb8) and
``camera/camera_info`` (:mod:`sim_server.soccer.cameras`), with ``base_link -> camera`` on
``/tf_static``; and the ball's truth on ``/simulator/balls`` (geometry_msgs/PoseArray in ``map``,
10 Hz). Its description ``extends`` the robot world's: to every client of the robot world (the
dashboard, behaviours, judges) this is that world, with one more body in it.
"""

from __future__ import annotations

import math

from services.runtime import NodeSettings
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import PoseArray, Quaternion, Transform, TransformStamped, Vector3
from shared_models.std_msgs import Header
from sim_server.robot.limits import TRUTH_EVERY_STEPS
from sim_server.robot.node import RobotSimNode
from sim_server.robot.settings import RobotSettings
from sim_server.robot.world import RobotWorldConfig
from sim_server.soccer.cameras import RobotCameras, camera_frame
from sim_server.soccer.limits import CAMERA_FORWARD_M, CAMERA_HEIGHT_M, CAMERA_PITCH_DEG
from sim_server.soccer.settings import SoccerSettings
from sim_server.soccer.world import SoccerWorld

__all__ = ["BALLS_TOPIC", "SoccerSimNode"]

BALLS_TOPIC = "/simulator/balls"
# base_link -> camera: ROS's optical frame (z ahead, x right, y down) turned down by the pitch.
_HALF_PITCH = math.radians(CAMERA_PITCH_DEG) / 2.0
_OPTICAL = (-0.5, 0.5, -0.5, 0.5)  # x, y, z, w: body axes (x ahead, z up) -> optical axes


def _pitched_optical() -> Quaternion:
    """The pitch about y, then the optical turn (Hamilton product, x y z w)."""
    sy, w1 = math.sin(_HALF_PITCH), math.cos(_HALF_PITCH)
    x2, y2, z2, w2 = _OPTICAL
    return Quaternion(
        x=w1 * x2 + sy * z2,
        y=w1 * y2 + sy * w2,
        z=w1 * z2 - sy * x2,
        w=w1 * w2 - sy * y2,
    )


def _build_world(sim: RobotSettings) -> SoccerWorld:
    return SoccerWorld(RobotWorldConfig(seed=sim.seed, robots=sim.robots, obstacles=sim.obstacles))


class SoccerSimNode(RobotSimNode):
    """The soccer room as a node; ``world`` is its :class:`SoccerWorld`."""

    WORLD_NAME = "soccer"

    def __init__(self, sim: SoccerSettings | None = None, settings: NodeSettings | None = None) -> None:
        super().__init__(sim or SoccerSettings(), settings, _build_world)
        self.world: SoccerWorld
        self.balls_publisher = self.create_publisher(PoseArray, BALLS_TOPIC, 10)
        self.cameras = RobotCameras(self, self.namespaces, self.world.robot_pose, lambda: self.world.client)

    def _reset_world(self) -> str:
        return super()._reset_world() + ", the ball on its spot"

    def _publish_tick(self, steps: int) -> None:
        super()._publish_tick(steps)
        if steps % TRUTH_EVERY_STEPS == 0:
            x, y = self.world.ball_position()
            header = self.header()
            self.balls_publisher.publish_built(
                lambda: PoseArray.model_validate(
                    {"header": header, "poses": [{"position": {"x": x, "y": y, "z": 0.0}, "orientation": {"w": 1.0}}]}
                )
            )

    def _static_transforms(self, stamp: Time) -> list[TransformStamped]:
        transforms = super()._static_transforms(stamp)
        rotation = _pitched_optical()
        for robot, namespace in zip(self.robots, self.namespaces, strict=True):
            transforms.append(
                TransformStamped(
                    header=Header(stamp=stamp, frame_id=robot.base_frame),
                    child_frame_id=camera_frame(namespace),
                    transform=Transform(
                        translation=Vector3(x=CAMERA_FORWARD_M, z=CAMERA_HEIGHT_M), rotation=rotation.model_copy()
                    ),
                )
            )
        return transforms
