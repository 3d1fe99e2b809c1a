"""The ball world as a node: ``/tiny/balls`` (geometry_msgs/PoseArray) at 30 Hz of sim time."""

from __future__ import annotations

from typing import Any

from services.runtime import NodeSettings
from shared_models.geometry_msgs import Point, Pose, PoseArray, Quaternion
from sim_server.camera import View, render_rgb
from sim_server.world_node import WorldNode
from tests.sim_server.tiny.settings import BallSettings
from tests.sim_server.tiny.world import BallWorld


def _build(sim: BallSettings) -> BallWorld:
    return BallWorld(sim.seed or 0, sim.balls)


class BallNode(WorldNode[BallSettings]):
    PUBLISH_EVERY_STEPS = 2
    WORLD_NAME = "tiny"

    def __init__(self, sim: BallSettings, settings: NodeSettings | None = None) -> None:
        super().__init__(sim, settings, _build)
        self.world: BallWorld
        self.balls = self.create_publisher(PoseArray, "/tiny/balls", 10)
        self._announce(f"{sim.balls} balls")

    def _publish_tick(self, steps: int) -> None:
        header = self.header()
        poses = [self.world.ball_pose(i) for i in range(len(self.world.balls))]
        self.balls.publish(
            PoseArray(
                header=header,
                poses=[
                    Pose(position=Point(x=x, y=y, z=z), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw))
                    for (x, y, z), (qx, qy, qz, qw) in poses
                ],
            )
        )

    def _reset_world(self) -> str:
        return "nothing to reset"

    def _publish_build(self) -> None:
        pass

    def _world_fields(self) -> dict[str, Any]:
        return {}

    def _render_camera(self, width: int, height: int) -> bytes:
        return render_rgb(self.world.client, View((0.0, -4.0, 1.0), (0.0, 0.0, 0.5)), width, height)
