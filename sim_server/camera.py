"""Cameras: the view from any eye in a world, as raw RGB or a JPEG (each world says where its
camera stands: the drone's chase view, the robot's forward view).

Two renderers, both headless: OpenGL through EGL (:mod:`sim_server.camera_gl`, Mesa's llvmpipe:
a few milliseconds a frame at 640x480) and PyBullet's software renderer (ER_TINY_RENDERER: tens
of milliseconds at 320x240, over a hundred at 640x480, holding the GIL meanwhile). ``auto`` (the
default) uses OpenGL where it can and otherwise PyBullet's, saying so once in the log. Both use
the same view and projection matrices, so a body appears in the same place in either. Pillow
encodes JPEGs. Render at a video rate, only while someone watches, never every step.
"""

from __future__ import annotations

import io
import logging
from typing import TYPE_CHECKING, Literal

import numpy as np
import pybullet as p

if TYPE_CHECKING:
    from sim_server.camera_gl import GlRenderer

__all__ = ["Renderer", "View", "encode_jpeg", "opengl_status", "render_rgb", "render_view_jpeg"]

Renderer = Literal["auto", "opengl", "pybullet"]
_log = logging.getLogger(__name__)

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


class _OpenGl:
    """This process's OpenGL renderer, opened on first use; why not, when it cannot be."""

    renderer: GlRenderer | None = None
    unavailable: str | None = None

    @classmethod
    def get(cls) -> GlRenderer | None:
        if cls.renderer is None and cls.unavailable is None:
            from sim_server.camera_gl import GlUnavailable, open_renderer

            try:
                cls.renderer = open_renderer()
            except GlUnavailable as error:
                cls.unavailable = str(error)
                _log.warning("camera: PyBullet's software renderer (slower: 7-10 frames a second at 640x480): %s", error)
        return cls.renderer


def opengl_status() -> str | None:
    """None when the camera can render with OpenGL here, else why it cannot (``skydeck doctor``)."""
    from sim_server.camera_gl import GlUnavailable, open_renderer

    try:
        open_renderer().close()
    except GlUnavailable as error:
        return str(error)
    return None


def render_rgb(client: int, view: View, width: int, height: int, *, renderer: Renderer = "auto") -> bytes:
    """The view in PyBullet client ``client`` as ``rgb8`` pixels: ``height`` rows of
    ``3 * width`` bytes, the top row first (sensor_msgs/Image's layout). ``renderer``: ``auto``
    (OpenGL, else PyBullet's), ``opengl`` (GlUnavailable if it cannot) or ``pybullet``."""
    if not (1 <= width <= MAX_SIDE and 1 <= height <= MAX_SIDE):
        raise ValueError(f"image size {width}x{height} is outside 1..{MAX_SIDE} pixels per side")
    view_matrix = p.computeViewMatrix(view.eye, view.target, (0.0, 0.0, 1.0), physicsClientId=client)
    projection = p.computeProjectionMatrixFOV(
        _FIELD_OF_VIEW_DEG, width / height, view.near_m, view.far_m, physicsClientId=client
    )
    if renderer != "pybullet":
        gl = _OpenGl.get()
        if gl is not None:
            return gl.render(client, view_matrix, projection, width, height)
        if renderer == "opengl":
            from sim_server.camera_gl import GlUnavailable

            raise GlUnavailable(_OpenGl.unavailable or "no OpenGL")
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
