"""Cameras: the view from any eye in a world, as raw RGB or a JPEG (each world says where its
camera stands: the drone's chase view, the robot's forward view).

Uses PyBullet's software renderer (ER_TINY_RENDERER), so it works headless, and Pillow to
encode. It is the camera's whole cost: tens of milliseconds at 320x240, about a hundred at
640x480 on one core, and PyBullet holds the GIL meanwhile (a thread would not help). Render at
a video rate, only while someone watches, never every step.
"""

from __future__ import annotations

import io

import numpy as np
import pybullet as p

__all__ = ["View", "encode_jpeg", "render_rgb", "render_view_jpeg"]

_FIELD_OF_VIEW_DEG = 60.0
_NEAR_M = 0.1
_FAR_M = 120.0
MAX_SIDE = 4096

Vector = tuple[float, float, float]


class View:
    """Where a camera stands and looks (z up), and its depth range."""

    __slots__ = ("eye", "far_m", "near_m", "target")

    def __init__(self, eye: Vector, target: Vector, *, near_m: float = _NEAR_M, far_m: float = _FAR_M) -> None:
        self.eye, self.target, self.near_m, self.far_m = eye, target, near_m, far_m


def render_rgb(client: int, view: View, width: int, height: int) -> bytes:
    """The view in PyBullet client ``client`` as ``rgb8`` pixels: ``height`` rows of
    ``3 * width`` bytes, the top row first (sensor_msgs/Image's layout)."""
    if not (1 <= width <= MAX_SIDE and 1 <= height <= MAX_SIDE):
        raise ValueError(f"image size {width}x{height} is outside 1..{MAX_SIDE} pixels per side")
    view_matrix = p.computeViewMatrix(view.eye, view.target, (0.0, 0.0, 1.0), physicsClientId=client)
    projection = p.computeProjectionMatrixFOV(
        _FIELD_OF_VIEW_DEG, width / height, view.near_m, view.far_m, physicsClientId=client
    )
    _, _, rgba, _, _ = p.getCameraImage(
        width,
        height,
        view_matrix,
        projection,
        renderer=p.ER_TINY_RENDERER,
        flags=p.ER_NO_SEGMENTATION_MASK,
        physicsClientId=client,
    )
    # PyBullet (built with numpy) hands back a (height, width, 4) array: drop alpha in one copy.
    pixels = np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)
    return pixels[:, :, :3].tobytes()


def encode_jpeg(rgb: bytes, width: int, height: int, quality: int = 70) -> bytes:
    """``rgb8`` pixels (as :func:`render_rgb` makes them) as a JPEG."""
    if not 1 <= quality <= 95:
        raise ValueError(f"quality={quality} is outside [1, 95] (Pillow's useful JPEG range)")
    from PIL import Image  # loaded once someone watches: the simulator starts without it

    out = io.BytesIO()
    Image.frombytes("RGB", (width, height), rgb).save(out, format="JPEG", quality=quality)
    return out.getvalue()


def render_view_jpeg(client: int, view: View, *, width: int = 320, height: int = 240, quality: int = 70) -> bytes:
    """The view in PyBullet client ``client`` as a JPEG."""
    if not 1 <= quality <= 95:  # before the costly render
        raise ValueError(f"quality={quality} is outside [1, 95] (Pillow's useful JPEG range)")
    return encode_jpeg(render_rgb(client, view, width, height), width, height, quality)
