"""The soccer room: the robot world with a ball the robots can push.

Example::

    from sim_server.soccer.world import SoccerWorld

    world = SoccerWorld(RobotWorldConfig(seed=1))
    world.set_cmd_vel(0, 0.3, 0.0)        # robot 0 drives at the ball ahead of it
    world.step(3 * world.PHYSICS_HZ)
    x, y = world.ball_position()          # pushed along

The ball is a dynamic sphere: it rolls, bounces off walls, boxes and people, and moves only by
contact (a robot's bumper, the person's legs); nothing ever sets its position but a reset. A
reset puts it back at its start with the robots, as a fresh world.
"""

from __future__ import annotations

import pybullet as p

from sim_server.robot.world import RobotWorld, RobotWorldConfig
from sim_server.soccer.limits import (
    BALL_ANGULAR_DAMPING,
    BALL_FRICTION,
    BALL_LINEAR_DAMPING,
    BALL_MASS_KG,
    BALL_RADIUS_M,
    BALL_RESTITUTION,
    BALL_RGBA,
    BALL_ROLLING_FRICTION,
    BALL_START_M,
)

__all__ = ["SoccerWorld", "create_ball"]

# Bullet's own filter group and mask for a dynamic body ("DefaultFilter", everything). The robot
# world's bodies all accept that group (it is the group of ray tests, which their masks let in),
# so the ball touches the floor, walls, boxes, robots and the person without the robot world's
# groups knowing of it. Its laser does not see the ball (its rays look for walls, robots, legs).
_DEFAULT_GROUP = 1
_EVERYTHING = -1


def create_ball(client: int, x: float, y: float) -> int:
    """The ball, resting on the floor at (x, y); its body id."""
    shape = p.createCollisionShape(p.GEOM_SPHERE, radius=BALL_RADIUS_M, physicsClientId=client)
    visual = p.createVisualShape(p.GEOM_SPHERE, radius=BALL_RADIUS_M, rgbaColor=BALL_RGBA, physicsClientId=client)
    ball = p.createMultiBody(BALL_MASS_KG, shape, visual, (x, y, BALL_RADIUS_M), physicsClientId=client)
    p.changeDynamics(
        ball, -1,
        lateralFriction=BALL_FRICTION, rollingFriction=BALL_ROLLING_FRICTION, restitution=BALL_RESTITUTION,
        linearDamping=BALL_LINEAR_DAMPING, angularDamping=BALL_ANGULAR_DAMPING, physicsClientId=client,
    )  # fmt: skip
    p.setCollisionFilterGroupMask(ball, -1, _DEFAULT_GROUP, _EVERYTHING, physicsClientId=client)
    return ball


class SoccerWorld(RobotWorld):
    """A robot world (``config``: its robots, boxes, seed) with a ball at BALL_START_M."""

    def __init__(self, config: RobotWorldConfig | None = None) -> None:
        self._ball = -1
        super().__init__(config)

    def ball_position(self) -> tuple[float, float]:
        """Where the ball's centre is over the floor (m)."""
        self._check_open()
        (x, y, _), _ = p.getBasePositionAndOrientation(self._ball, physicsClientId=self._client)
        return x, y

    def ball_speed(self) -> float:
        """How fast the ball moves over the floor (m/s)."""
        self._check_open()
        (vx, vy, _), _ = p.getBaseVelocity(self._ball, physicsClientId=self._client)
        return float((vx * vx + vy * vy) ** 0.5)

    def _build(self) -> None:
        super()._build()
        self._ball = create_ball(self._client, *BALL_START_M)
