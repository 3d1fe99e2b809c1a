"""``cv_bridge.CvBridgeError``: what cv_bridge raises when an image cannot be converted."""

from __future__ import annotations

from shared_models.errors import SkydeckError

__all__ = ["CvBridgeError"]


class CvBridgeError(SkydeckError, TypeError):
    """An image or message cv_bridge cannot convert; the message says why (a TypeError, as ROS's)."""
