"""Skydeck's optional extras a ROS program may need, and the one line that says how to get one.

DESIGN.md keeps heavy dependencies out of the default install. A program that imports a module
of an extra that is not installed (``import cv2``, ``from cv_bridge import CvBridge`` without
OpenCV) is told, in one line, what to install, instead of Python's bare "No module named".
"""

from __future__ import annotations

import importlib.machinery

from services.ros.errors import RosFacadeError

__all__ = ["EXTRAS", "MissingExtraError", "check_extra"]

# module a program imports -> (the module it needs, what that is, the extra that brings it)
EXTRAS = {
    "cv2": ("cv2", "OpenCV", "vision"),
    "cv_bridge": ("cv2", "OpenCV", "vision"),
}


class MissingExtraError(RosFacadeError, ImportError):
    """A module of one of Skydeck's extras, which is not installed here."""


def check_extra(name: str) -> None:
    """Raise MissingExtraError if ``name`` needs an extra that is not installed."""
    needed, what, extra = EXTRAS[name]
    # The path finder only: asking importlib.util.find_spec would ask the ROS finder again.
    if importlib.machinery.PathFinder.find_spec(needed) is None:
        needs = f"`{name}` ({what})" if name == needed else f"`{name}` needs {what}, which"
        raise MissingExtraError(
            f"{needs} is in Skydeck's {extra} extra, not installed here: "
            f"install it with `make install-{extra}` (or `pip install 'skydeck[{extra}]'`)"
        )
