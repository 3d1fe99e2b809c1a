"""What a world tells its clients before it runs: its numbers and the names of its topics and
services (``GET /api/config`` serves it; the dashboard draws and subscribes from it).

Each world's package declares one (``sim_server.drone.description``...), from its own limits,
loading no PyBullet; the table of worlds (:mod:`sim_server.worlds`) points at it.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = ["WorldDescription"]


@dataclass(frozen=True, slots=True)
class WorldDescription:
    """A world's constants and names.

    ``constants``: what clients must agree on (the arena's size, the robot's radius...), in SI
    units with the unit in the name. ``topics`` and ``services``: the names the world's system
    uses, by role (``{"pose": "/drone/pose"}``), the simulator's and its workshop nodes'; a
    relative name (``odom``) is one per robot, under each namespace ``/simulator/world`` lists.
    Every world also has the floor's names (``/clock``, ``/simulator/world``, the camera,
    ``/simulator/reset``), which are not repeated here. ``extends``: the world this one is built
    on, whose every constant and name it keeps (the soccer room is the robot world with a ball),
    so a client of that world may show this one as it (the dashboard does).
    """

    constants: Mapping[str, Any]
    topics: Mapping[str, str] = field(default_factory=dict)
    services: Mapping[str, str] = field(default_factory=dict)
    extends: str | None = None

    def config(self) -> dict[str, Any]:
        """The world's part of ``/api/config``: its constants, its names under ``topics`` and
        ``services``, and ``extends`` if it has one."""
        extends = {"extends": self.extends} if self.extends else {}
        return {**self.constants, "topics": dict(self.topics), "services": dict(self.services), **extends}
