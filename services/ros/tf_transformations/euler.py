"""Euler angles in all 24 conventions, named as ROS's ``tf.transformations`` names them.

An ``axes`` string is a frame letter and three axes: ``'sxyz'`` (the default: roll about x,
pitch about y, yaw about z, each about the Static, fixed axes), ``'rzyx'`` (about the Rotating
axes: z first, then the new y, then the newer x), or a proper Euler sequence such as ``'szxz'``.
For angles ``(ai, aj, ak)`` and axes ``p, q, r``:

    's' + pqr:  R = R_r(ak) @ R_q(aj) @ R_p(ai)      (ai about p acts first)
    'r' + pqr:  R = R_p(ai) @ R_q(aj) @ R_r(ak)

so ``'rzyx'`` with ``(yaw, pitch, roll)`` is ``'sxyz'`` with ``(roll, pitch, yaw)``.

Reading angles back from a matrix maps any convention onto two solved ones (``'sxyz'`` for
three different axes, ``'sxyx'`` for a repeated one) by relabelling the axes. The middle angle
comes back in [-pi/2, pi/2] (three axes) or [0, pi] (repeated); at gimbal lock, where only a sum
of the other two is defined, the last-applied angle is set to 0.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from services.ros.tf_transformations.matrices import EPS, Array
from services.ros.tf_transformations.quaternions import quaternion_matrix, quaternion_multiply

__all__ = [
    "AXES",
    "euler_from_matrix",
    "euler_from_quaternion",
    "euler_matrix",
    "quaternion_from_euler",
]

_AXIS = {"x": 0, "y": 1, "z": 2}
_SEQUENCES = ("xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz")
AXES = tuple(frame + sequence for frame in "sr" for sequence in _SEQUENCES)
"""The 24 conventions ``axes`` may name."""


def _parse(axes: Any) -> tuple[bool, tuple[int, int, int]]:
    """(rotating frame?, the three axis indices in the order they are written)."""
    if not (isinstance(axes, str) and axes in AXES):
        raise ValueError(f"unknown axes {axes!r}: one of 'sxyz' (the default), 'rzyx', ... ({', '.join(AXES)})")
    p, q, r = (_AXIS[c] for c in axes[1:])
    return axes[0] == "r", (p, q, r)


def _in_static_order(axes: Any, ai: float, aj: float, ak: float) -> tuple[tuple[int, int, int], tuple[float, float, float]]:
    """The convention as three rotations about fixed axes, first applied first."""
    rotating, (p, q, r) = _parse(axes)
    if rotating:  # R_p(ai) R_q(aj) R_r(ak) = ak about r first, then aj about q, then ai about p
        return (r, q, p), (ak, aj, ai)
    return (p, q, r), (ai, aj, ak)


def _elementary(axis: int, angle: float) -> Array:
    c, s = math.cos(angle), math.sin(angle)
    j, k = (axis + 1) % 3, (axis + 2) % 3
    matrix = np.identity(4)
    matrix[j, j], matrix[j, k], matrix[k, j], matrix[k, k] = c, -s, s, c
    return matrix


def euler_matrix(ai: float, aj: float, ak: float, axes: str = "sxyz") -> Array:
    """The 4x4 rotation matrix of Euler angles ``ai, aj, ak`` (radians) in the ``axes`` convention."""
    order, angles = _in_static_order(axes, ai, aj, ak)
    matrix = np.identity(4)
    for axis, angle in zip(order, angles, strict=True):
        matrix = _elementary(axis, angle) @ matrix
    return matrix


def quaternion_from_euler(ai: float, aj: float, ak: float, axes: str = "sxyz") -> Array:
    """The quaternion ``[x, y, z, w]`` of Euler angles (radians) in the ``axes`` convention:
    ``quaternion_from_euler(roll, pitch, yaw)``."""
    order, angles = _in_static_order(axes, ai, aj, ak)
    q = np.array([0.0, 0.0, 0.0, 1.0])
    for axis, angle in zip(order, angles, strict=True):
        step = np.zeros(4)
        step[axis] = math.sin(angle / 2.0)
        step[3] = math.cos(angle / 2.0)
        q = quaternion_multiply(step, q)
    return q


def euler_from_matrix(matrix: Any, axes: str = "sxyz") -> tuple[float, float, float]:
    """The Euler angles ``(ai, aj, ak)`` of a rotation matrix (3x3 or 4x4) in the ``axes``
    convention (see the module docstring for their ranges)."""
    rotating, (p, q, r) = _parse(axes)
    if rotating:
        p, r = r, p  # solved as the static convention that applies the same rotations
    rotation = np.asarray(matrix, dtype=np.float64)[:3, :3]
    if p == r:  # a proper Euler sequence: relabel p -> x, q -> y, the third axis -> z
        k = 3 - p - q
        first, middle, last = _solve_repeated(rotation[np.ix_((p, q, k), (p, q, k))])
        labels = (p, q, k)
    else:
        first, middle, last = _solve_three(rotation[np.ix_((p, q, r), (p, q, r))])
        labels = (p, q, r)
    if not _even(labels):  # the relabelling is a reflection: it turns every angle round
        first, middle, last = -first, -middle, -last
    return (last, middle, first) if rotating else (first, middle, last)


def _even(labels: tuple[int, int, int]) -> bool:
    return labels in ((0, 1, 2), (1, 2, 0), (2, 0, 1))


def _solve_three(m: Array) -> tuple[float, float, float]:
    """(a, b, c) with m = Rz(c) Ry(b) Rx(a)."""
    cos_b = math.hypot(m[0, 0], m[1, 0])
    if cos_b > EPS:
        return math.atan2(m[2, 1], m[2, 2]), math.atan2(-m[2, 0], cos_b), math.atan2(m[1, 0], m[0, 0])
    return math.atan2(-m[1, 2], m[1, 1]), math.atan2(-m[2, 0], cos_b), 0.0


def _solve_repeated(m: Array) -> tuple[float, float, float]:
    """(a, b, c) with m = Rx(c) Ry(b) Rx(a)."""
    sin_b = math.hypot(m[0, 1], m[0, 2])
    if sin_b > EPS:
        return math.atan2(m[0, 1], m[0, 2]), math.atan2(sin_b, m[0, 0]), math.atan2(m[1, 0], -m[2, 0])
    return math.atan2(-m[1, 2], m[1, 1]), math.atan2(sin_b, m[0, 0]), 0.0


def euler_from_quaternion(quaternion: Any, axes: str = "sxyz") -> tuple[float, float, float]:
    """The Euler angles of a quaternion ``[x, y, z, w]``: ``roll, pitch, yaw =
    euler_from_quaternion([q.x, q.y, q.z, q.w])``."""
    return euler_from_matrix(quaternion_matrix(quaternion), axes)

