"""Balls dropped from 2 m onto a ground, in PyBullet, at 60 Hz."""

from __future__ import annotations

import pybullet as p

from sim_server.bullet import BulletWorld
from sim_server.geometry import Pose

BALL_RADIUS_M = 0.2


class BallWorld(BulletWorld):
    """``balls`` balls in a row, falling from 2 m."""

    PHYSICS_HZ = 60

    def __init__(self, seed: int, balls: int) -> None:
        super().__init__()
        self.seed = seed
        client = self._fresh_simulation()
        ground = p.createCollisionShape(p.GEOM_PLANE, physicsClientId=client)
        p.createMultiBody(0.0, ground, physicsClientId=client)
        shape = p.createCollisionShape(p.GEOM_SPHERE, radius=BALL_RADIUS_M, physicsClientId=client)
        look = p.createVisualShape(p.GEOM_SPHERE, radius=BALL_RADIUS_M, rgbaColor=(0.9, 0.2, 0.2, 1.0), physicsClientId=client)
        self.balls = [
            p.createMultiBody(1.0, shape, look, (float(i), 0.0, 2.0), physicsClientId=client) for i in range(balls)
        ]

    def step(self, n: int = 1) -> None:
        self._check_open()
        for _ in range(n):
            p.stepSimulation(physicsClientId=self._client)
            self._steps += 1

    def ball_pose(self, index: int) -> Pose:
        return p.getBasePositionAndOrientation(self.balls[index], physicsClientId=self._client)
