"""Cameras: the view from behind and above the drone, or from any eye, as a JPEG.

Uses PyBullet's software renderer (ER_TINY_RENDERER), so it works headless, and Pillow to
encode. Costs a few milliseconds per frame at 320x240; call it at a video rate, not every step.
"""

from __future__ import annotations

import io
import math

import pybullet as p
from PIL import Image

from sim_server.world import World, yaw_of

__all__ = ["render_jpeg", "render_view_jpeg"]

_CHASE_DISTANCE_M = 6.0
_CHASE_HEIGHT_M = 3.0
_FIELD_OF_VIEW_DEG = 60.0
_NEAR_M = 0.1
_FAR_M = 120.0


def render_jpeg(world: World, width: int = 320, height: int = 240, quality: int = 70) -> bytes:
    """Render the chase view of ``world`` and return it as JPEG bytes.

    Example::

        frame = render_jpeg(world)            # 320x240, quality 70
        Path("view.jpg").write_bytes(frame)
    """
    (x, y, z), orientation = world.drone_pose()
    yaw = yaw_of(orientation)
    eye = (
        x - _CHASE_DISTANCE_M * math.cos(yaw),
        y - _CHASE_DISTANCE_M * math.sin(yaw),
        z + _CHASE_HEIGHT_M,
    )
    return render_view_jpeg(
        world.client, eye, (x, y, z), width=width, height=height, quality=quality, far_m=_FAR_M
    )


def render_view_jpeg(
    client: int,
    eye: tuple[float, float, float],
    target: tuple[float, float, float],
    *,
    width: int = 320,
    height: int = 240,
    quality: int = 70,
    field_of_view_deg: float = _FIELD_OF_VIEW_DEG,
    near_m: float = _NEAR_M,
    far_m: float = _FAR_M,
) -> bytes:
    """The view from ``eye`` towards ``target`` (z up) in PyBullet client ``client``, as JPEG."""
    if not (1 <= width <= 4096 and 1 <= height <= 4096):
        raise ValueError(f"image size {width}x{height} is outside 1..4096 pixels per side")
    if not 1 <= quality <= 95:
        raise ValueError(f"quality={quality} is outside [1, 95] (Pillow's useful JPEG range)")
    view = p.computeViewMatrix(eye, target, (0.0, 0.0, 1.0), physicsClientId=client)
    projection = p.computeProjectionMatrixFOV(
        field_of_view_deg, width / height, near_m, far_m, physicsClientId=client
    )
    _, _, rgba, _, _ = p.getCameraImage(
        width,
        height,
        view,
        projection,
        renderer=p.ER_TINY_RENDERER,
        flags=p.ER_NO_SEGMENTATION_MASK,
        physicsClientId=client,
    )
    image = Image.frombytes("RGBA", (width, height), bytes(rgba)).convert("RGB")
    out = io.BytesIO()
    image.save(out, format="JPEG", quality=quality)
    return out.getvalue()
