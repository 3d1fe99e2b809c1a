"""The drone world's camera: behind and above the drone, looking at it (a chase view)."""

from __future__ import annotations

import math

from sim_server.camera import View, render_view_jpeg
from sim_server.drone.world import World
from sim_server.geometry import yaw_of

__all__ = ["chase_view", "render_jpeg"]

_CHASE_DISTANCE_M = 6.0
_CHASE_HEIGHT_M = 3.0


def chase_view(world: World) -> View:
    """Behind and above the drone, looking at it."""
    (x, y, z), orientation = world.drone_pose()
    yaw = yaw_of(orientation)
    eye = (x - _CHASE_DISTANCE_M * math.cos(yaw), y - _CHASE_DISTANCE_M * math.sin(yaw), z + _CHASE_HEIGHT_M)
    return View(eye, (x, y, z))


def render_jpeg(world: World, width: int = 320, height: int = 240, quality: int = 70) -> bytes:
    """Render the chase view of ``world`` and return it as JPEG bytes.

    Example::

        frame = render_jpeg(world)            # 320x240, quality 70
        Path("view.jpg").write_bytes(frame)
    """
    return render_view_jpeg(world.client, chase_view(world), width=width, height=height, quality=quality)
