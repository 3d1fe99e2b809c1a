"""What every simulated world stands on: a PyBullet client of its own, the steps it has taken
(sim time), and a lifecycle (``close``, or a ``with`` block).

Every world's simulation is one (the drone's :class:`~sim_server.drone.world.World`, the robot
world's :class:`~sim_server.robot.world.RobotWorld`); a world builds its bodies on a fresh
simulation (:meth:`BulletWorld._fresh_simulation`) and steps it at its own ``PHYSICS_HZ`` (the
drone world at 240 Hz; the robot world, slower, at 120 Hz), under its ``GRAVITY_M_S2``.
"""

from __future__ import annotations

from types import TracebackType
from typing import ClassVar, Self

import pybullet as p

__all__ = ["STANDARD_GRAVITY_M_S2", "BulletWorld"]

STANDARD_GRAVITY_M_S2 = 9.81


class BulletWorld:
    """A headless PyBullet client (``p.DIRECT``) and its clock. Not thread-safe."""

    PHYSICS_HZ: ClassVar[int]
    """Physics steps per sim second in this kind of world (each world says)."""
    GRAVITY_M_S2: ClassVar[float] = STANDARD_GRAVITY_M_S2
    """Downward acceleration; a world whose controller relies on it sets its own."""

    def __init__(self) -> None:
        self._steps = 0
        self._closed = False
        self._client = p.connect(p.DIRECT)

    def close(self) -> None:
        """Disconnect the PyBullet client. Idempotent."""
        if not self._closed:
            self._closed = True
            p.disconnect(physicsClientId=self._client)

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    @property
    def client(self) -> int:
        """The PyBullet physics client id of this world (for rendering)."""
        self._check_open()
        return self._client

    @property
    def time_s(self) -> float:
        """Sim time: 1/PHYSICS_HZ s per physics step since the world was created."""
        return self._steps * (1.0 / self.PHYSICS_HZ)

    @property
    def steps(self) -> int:
        """Physics steps taken since the world was created."""
        return self._steps

    def _check_steps(self, n: int) -> None:
        """What every world's ``step(n)`` checks first: the world is open and ``n`` is no less than 0."""
        self._check_open()
        if n < 0:
            raise ValueError(f"n={n} must be >= 0")

    def _check_open(self) -> None:
        if self._closed:
            name = type(self).__name__
            raise RuntimeError(f"this {name} is closed; create a new {name} to keep simulating")

    def _fresh_simulation(self) -> int:
        """Remove every body and start the simulation over (gravity, time step); the client.

        A full rebuild, so a world after a reset is exactly a fresh one: no contact caches or
        solver state survive. The clock keeps running."""
        client = self._client
        p.resetSimulation(physicsClientId=client)
        p.setGravity(0.0, 0.0, -self.GRAVITY_M_S2, physicsClientId=client)
        p.setTimeStep(1.0 / self.PHYSICS_HZ, physicsClientId=client)
        return client
