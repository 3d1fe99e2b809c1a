"""``cv_bridge``: ROS images to OpenCV images and back, as ROS 1's and ROS 2's cv_bridge do.

    from cv_bridge import CvBridge
    bridge = CvBridge()
    frame = bridge.imgmsg_to_cv2(msg, desired_encoding='bgr8')

Over the real OpenCV, Skydeck's vision extra (``make install-vision``); without it, ``import
cv_bridge`` says so in one line (:mod:`services.ros.extras`). See :mod:`.core`.
"""

from __future__ import annotations

from services.ros.cv_bridge.core import CvBridge, getCvType
from services.ros.cv_bridge.errors import CvBridgeError

__all__ = ["CvBridge", "CvBridgeError", "getCvType"]
