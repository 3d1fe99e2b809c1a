"""Poses as PyBullet gives them, and the heading of an orientation: what every world reads."""

from __future__ import annotations

import math

__all__ = ["Pose", "Quaternion", "Vector3", "yaw_of"]

Vector3 = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]
"""(x, y, z, w), PyBullet's order."""
Pose = tuple[Vector3, Quaternion]


def yaw_of(q: Quaternion) -> float:
    """Heading (rotation about world z) of an orientation quaternion (x, y, z, w), in rad."""
    qx, qy, qz, qw = q
    return math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
