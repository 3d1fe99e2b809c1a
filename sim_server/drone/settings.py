"""The drone world's options: ``--boxes`` (``SKYDECK_SIM_BOXES``), beside every world's
(:class:`sim_server.settings.SimSettings`). Pure settings: importing this loads no PyBullet."""

from __future__ import annotations

from pydantic import Field

from sim_server.drone.limits import DEFAULT_BOXES, MAX_BOXES
from sim_server.settings import SimSettings

__all__ = ["DroneSettings"]


class DroneSettings(SimSettings):
    """The drone world's settings."""

    boxes: int = Field(
        default=DEFAULT_BOXES,
        ge=0,
        le=MAX_BOXES,
        description=f"number of falling boxes, 0-{MAX_BOXES} (default {DEFAULT_BOXES})",
    )
