"""What a recorded run is made of: poses in time, boxes on the floor, bumps."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Box", "BumpEvent", "Pose"]


@dataclass(frozen=True, slots=True)
class Pose:
    """Where something was at sim time ``t``: x, y, z (m), heading (rad)."""

    t: float
    x: float
    y: float
    yaw: float = 0.0
    z: float = 0.0


@dataclass(frozen=True, slots=True)
class Box:
    """An oriented box on the floor (a wall or an obstacle): centre, sides, heading."""

    x: float
    y: float
    size_x: float
    size_y: float
    yaw: float
    kind: str
    """``wall``, ``obstacle`` (the robot world) or ``box`` (the drone world's)."""


@dataclass(frozen=True, slots=True)
class BumpEvent:
    t: float
    x: float
    y: float
    parts: tuple[str, ...]
