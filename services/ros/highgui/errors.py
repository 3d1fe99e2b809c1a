"""``HighGuiError``: what Skydeck's OpenCV windows raise, a ``cv2.error`` as OpenCV's own is.

Raised for a call the windows cannot honour: an image that cannot be shown, a window or trackbar
that does not exist, an argument of the wrong kind, a HighGUI function Skydeck does not provide.
A program's ``except cv2.error:`` catches it; ``skydeck run`` prints it as one line.
"""

from __future__ import annotations

import cv2

from shared_models.errors import SkydeckError

__all__ = ["HighGuiError"]


class HighGuiError(SkydeckError, cv2.error):
    """An OpenCV window call Skydeck cannot honour; the message says why and what to do."""
