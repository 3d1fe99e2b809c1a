"""What a window shows: when Skydeck serves the windows, and an image as ``imshow`` shows it.

OpenCV's rules for ``imshow`` (its documentation): 8-bit unsigned pixels as they are, 16-bit
unsigned divided by 256, 32- and 64-bit floats multiplied by 255 (so [0, 1] fills the range);
one channel is grey, three are BGR, four BGRA (the alpha is not shown). Anything else is an
error that says what to convert it to, where OpenCV's own would be a bare assertion.
"""

from __future__ import annotations

import os
from types import ModuleType
from typing import Any

import cv2
import numpy as np

from services.ros.highgui.errors import HighGuiError

__all__ = ["JPEG_QUALITY", "MAX_SIDE", "displayable", "encode_jpeg", "serves_windows"]

JPEG_QUALITY = 80
MAX_SIDE = 65_500  # JPEG's limit is 65,535 pixels a side
_DISPLAY_VARIABLES = ("DISPLAY", "WAYLAND_DISPLAY")


def serves_windows(cv2_module: ModuleType) -> bool:
    """Whether Skydeck serves this process's OpenCV windows: when OpenCV has no window system of
    its own (the headless build of Skydeck's vision extra) or there is no display to open a
    window on. Read once, when ``cv2`` is imported; these describe the machine, not Skydeck, so
    they are not settings."""
    framework = getattr(cv2_module, "currentUIFramework", lambda: "")()
    return not framework or not any(os.environ.get(name) for name in _DISPLAY_VARIABLES)


def displayable(winname: str, mat: Any) -> np.ndarray:
    """``mat`` as ``imshow`` shows it: a new uint8 array, grey (h x w) or BGR (h x w x 3)."""
    where = f"cv2.imshow({winname!r}, ...)"
    if mat is None:
        raise HighGuiError(f"{where}: the image is None (did cv2.imread fail, or has no frame come yet?)")
    if isinstance(mat, cv2.UMat):
        mat = mat.get()
    if not isinstance(mat, np.ndarray):
        raise HighGuiError(f"{where}: the image must be a numpy array (or a cv2.UMat), not {type(mat).__name__}")
    if mat.ndim == 3 and mat.shape[2] == 1:
        mat = mat[:, :, 0]
    if mat.ndim not in (2, 3) or mat.shape[0] == 0 or mat.shape[1] == 0:
        raise HighGuiError(f"{where}: an image has height x width (x channels) pixels, this array is {mat.shape}")
    if mat.ndim == 3 and mat.shape[2] not in (3, 4):
        raise HighGuiError(f"{where}: {mat.shape[2]} channels cannot be shown: grey (1), BGR (3) or BGRA (4)")
    if max(mat.shape[:2]) > MAX_SIDE:
        raise HighGuiError(f"{where}: {mat.shape[1]}x{mat.shape[0]} is too large to show ({MAX_SIDE} pixels a side at most)")
    shown = _to_uint8(where, mat)
    if shown.ndim == 3 and shown.shape[2] == 4:
        return cv2.cvtColor(shown, cv2.COLOR_BGRA2BGR)
    return shown


def _to_uint8(where: str, mat: np.ndarray) -> np.ndarray:
    if mat.dtype == np.uint8:
        return np.array(mat, copy=True, order="C")  # the program may draw on its array next
    if mat.dtype == np.uint16:
        return (mat >> 8).astype(np.uint8)
    if mat.dtype in (np.float32, np.float64):
        return np.clip(np.nan_to_num(mat) * 255.0 + 0.5, 0, 255).astype(np.uint8)
    raise HighGuiError(
        f"{where}: {mat.dtype} pixels cannot be shown (uint8, uint16, float32 or float64): "
        "convert them, e.g. with cv2.convertScaleAbs(image) or cv2.normalize(..., dtype=cv2.CV_8U)"
    )


def encode_jpeg(image: np.ndarray) -> bytes:
    """A :func:`displayable` image as a JPEG (grey stays grey)."""
    ok, encoded = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, JPEG_QUALITY])
    if not ok:  # cannot happen for a displayable image; said plainly if it ever does
        raise HighGuiError(f"OpenCV could not encode a {image.shape} image as JPEG")
    return encoded.tobytes()
