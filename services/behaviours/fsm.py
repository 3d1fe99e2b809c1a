"""A finite-state controller that chains two behaviours: drive squares until something is
close, then follow the wall.

It starts in ``drive_square`` (the :mod:`drive_square` behaviour, over and over) and watches the
laser: anything within ``near`` metres ahead (within 30 degrees) is the event that moves it to
``follow_wall`` (the :mod:`wall_follower` behaviour, keeping the wall on ``wall_side``), which
it keeps. Each state is one behaviour's controller; the machine only decides which one drives,
and says so: the state is published on ``fsm/state`` (std_msgs/String, latched) whenever it
changes, so a dashboard, a test or another node can follow it.

    skydeck run fsm --ros-args -p side:=4.0
    skydeck topic echo /fsm/state
"""

from __future__ import annotations

from services.behaviours.drive_square import SquareDriver
from services.behaviours.laser import nearest_in_sector
from services.behaviours.robot import RobotBehaviour, run_behaviour
from services.behaviours.wall_follower import WallFollower
from services.runtime import NodeSettings
from shared_models.std_msgs import String

__all__ = ["SquareThenWall", "main"]

SQUARE = "drive_square"
WALL = "follow_wall"
_NEAR_HALF_ANGLE_DEG = 30.0


class SquareThenWall(RobotBehaviour):
    """``fsm``: ``drive_square`` -> (something near ahead) -> ``follow_wall``."""

    def __init__(self, namespace: str = "/", settings: NodeSettings | None = None) -> None:
        super().__init__("fsm", namespace, settings)
        self.declare_parameter("side", 1.0)  # m, the square's side
        self.declare_parameter("speed", 0.2)  # m/s, in both states
        self.declare_parameter("near", 0.5)  # m: something this close ahead ends the squares
        self.declare_parameter("wall_side", "right")  # the side the wall is kept on
        self.declare_parameter("wall_distance", 0.5)  # m
        self.state_publisher = self.create_publisher(String, "fsm/state", 1, latched=True)
        self.square = self._new_square()
        self.follower = WallFollower(
            self.get_parameter("wall_side").value, self.get_parameter("wall_distance").value, self.get_parameter("speed").value
        )
        self.state = ""
        self._enter(SQUARE, "starting")

    def _new_square(self) -> SquareDriver:
        return SquareDriver(self.get_parameter("side").value, self.get_parameter("speed").value, 0.6)

    def _enter(self, state: str, why: str) -> None:
        self.state = state
        self.state_publisher.publish(String(data=state))
        self.get_logger().info("state %s (%s)", state, why)

    def control(self) -> tuple[float, float] | None:
        scan, pose = self.sensors.scan, self.sensors.pose
        if scan is None or pose is None:
            return None
        if self.state == SQUARE:
            near = nearest_in_sector(scan, 0.0, _NEAR_HALF_ANGLE_DEG)
            if near < self.get_parameter("near").value:
                self._enter(WALL, f"something {near:.2f} m ahead")
            else:
                if self.square.done:
                    self.square = self._new_square()  # and round again
                return self.square.update(pose)
        follower = self.follower
        follower.side = self.get_parameter("wall_side").value
        follower.distance = self.get_parameter("wall_distance").value
        follower.speed = self.get_parameter("speed").value
        return follower.update(scan)


def main(argv: list[str] | None = None) -> int:
    """``skydeck run fsm``."""
    return run_behaviour(SquareThenWall, argv, prog="fsm", description=__doc__.splitlines()[0])
