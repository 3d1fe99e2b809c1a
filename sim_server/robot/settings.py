"""The robot world's options: ``--robots`` and ``--obstacles`` (``SKYDECK_SIM_ROBOTS``...),
beside every world's (:class:`sim_server.settings.SimSettings`). Pure settings: importing this
loads no PyBullet."""

from __future__ import annotations

from pydantic import Field

from sim_server.robot.limits import DEFAULT_OBSTACLES, MAX_OBSTACLES, MAX_ROBOTS
from sim_server.settings import SimSettings

__all__ = ["RobotSettings"]


class RobotSettings(SimSettings):
    """The robot world's settings."""

    robots: int = Field(
        default=1, ge=1, le=MAX_ROBOTS, description=f"number of robots, 1-{MAX_ROBOTS} (default 1), under /robot1, /robot2..."
    )
    obstacles: int = Field(
        default=DEFAULT_OBSTACLES,
        ge=0,
        le=MAX_OBSTACLES,
        description=f"number of box obstacles, 0-{MAX_OBSTACLES} (default {DEFAULT_OBSTACLES})",
    )
