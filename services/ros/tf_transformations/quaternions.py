"""Quaternions as ROS orders them, ``[x, y, z, w]``: products, inverses, interpolation, and
conversion to and from rotation matrices.

``quaternion_multiply(q1, q0)`` is the Hamilton product ``q1 q0``: the rotation ``q0`` followed
by ``q1``, as matrices multiply (``quaternion_matrix(q1) @ quaternion_matrix(q0)``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from services.ros.tf_transformations.matrices import EPS, Array, unit_vector

__all__ = [
    "quaternion_about_axis",
    "quaternion_conjugate",
    "quaternion_from_matrix",
    "quaternion_imag",
    "quaternion_inverse",
    "quaternion_matrix",
    "quaternion_multiply",
    "quaternion_real",
    "quaternion_slerp",
    "random_quaternion",
    "random_rotation_matrix",
]


def _quaternion(q: Any) -> Array:
    array = np.array(q, dtype=np.float64, copy=True)
    if array.shape != (4,):
        raise ValueError(f"a quaternion is 4 numbers [x, y, z, w]; got shape {array.shape}")
    return array


def quaternion_matrix(quaternion: Any) -> Array:
    """The 4x4 rotation matrix of ``quaternion`` (normalised first; zero gives the identity)."""
    x, y, z, w = _quaternion(quaternion)
    n = x * x + y * y + z * z + w * w
    matrix = np.identity(4)
    if n < EPS:
        return matrix
    s = 2.0 / n
    matrix[:3, :3] = [
        [1.0 - s * (y * y + z * z), s * (x * y - z * w), s * (x * z + y * w)],
        [s * (x * y + z * w), 1.0 - s * (x * x + z * z), s * (y * z - x * w)],
        [s * (x * z - y * w), s * (y * z + x * w), 1.0 - s * (x * x + y * y)],
    ]
    return matrix


def quaternion_from_matrix(matrix: Any) -> Array:
    """The unit quaternion of a rotation matrix (3x3, or the rotation part of a 4x4), w >= 0."""
    r = np.asarray(matrix, dtype=np.float64)[:3, :3]
    trace = r[0, 0] + r[1, 1] + r[2, 2]
    # Take the square root of the largest of 4w^2, 4x^2, 4y^2, 4z^2 (Shepperd): never near zero,
    # so the other three, divided by it, stay accurate.
    if trace > 0.0:
        s = 2.0 * math.sqrt(trace + 1.0)
        q = [(r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s, s / 4.0]
    elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
        s = 2.0 * math.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2])
        q = [s / 4.0, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s, (r[2, 1] - r[1, 2]) / s]
    elif r[1, 1] > r[2, 2]:
        s = 2.0 * math.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2])
        q = [(r[0, 1] + r[1, 0]) / s, s / 4.0, (r[1, 2] + r[2, 1]) / s, (r[0, 2] - r[2, 0]) / s]
    else:
        s = 2.0 * math.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1])
        q = [(r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, s / 4.0, (r[1, 0] - r[0, 1]) / s]
    result = np.array(q)
    return -result if result[3] < 0.0 else result


def quaternion_multiply(quaternion1: Any, quaternion0: Any) -> Array:
    """The Hamilton product ``quaternion1 * quaternion0`` (``quaternion0`` rotates first)."""
    x1, y1, z1, w1 = _quaternion(quaternion1)
    x0, y0, z0, w0 = _quaternion(quaternion0)
    return np.array(
        [
            w1 * x0 + x1 * w0 + y1 * z0 - z1 * y0,
            w1 * y0 - x1 * z0 + y1 * w0 + z1 * x0,
            w1 * z0 + x1 * y0 - y1 * x0 + z1 * w0,
            w1 * w0 - x1 * x0 - y1 * y0 - z1 * z0,
        ]
    )


def quaternion_conjugate(quaternion: Any) -> Array:
    """``[-x, -y, -z, w]``."""
    q = _quaternion(quaternion)
    q[:3] = -q[:3]
    return q


def quaternion_inverse(quaternion: Any) -> Array:
    """The conjugate divided by the squared norm (for a unit quaternion, the conjugate)."""
    q = quaternion_conjugate(quaternion)
    return q / float(np.dot(q, q))


def quaternion_real(quaternion: Any) -> float:
    """The real part, w."""
    return float(_quaternion(quaternion)[3])


def quaternion_imag(quaternion: Any) -> Array:
    """The imaginary part, ``[x, y, z]``."""
    return _quaternion(quaternion)[:3].copy()


def quaternion_about_axis(angle: float, axis: Any) -> Array:
    """The rotation by ``angle`` (radians) about ``axis``."""
    direction = np.asarray(unit_vector(np.asarray(axis, dtype=np.float64)[:3]))
    half = angle / 2.0
    return np.array([*(direction * math.sin(half)), math.cos(half)])


def quaternion_slerp(quat0: Any, quat1: Any, fraction: float, spin: int = 0, shortestpath: bool = True) -> Array:
    """Spherical linear interpolation: ``quat0`` at 0, ``quat1`` at 1, at constant angular speed
    in between (the shorter way round unless ``shortestpath`` is False; ``spin`` extra half turns)."""
    q0 = np.asarray(unit_vector(_quaternion(quat0)))
    q1 = np.asarray(unit_vector(_quaternion(quat1)))
    if fraction == 0.0:
        return q0
    if fraction == 1.0:
        return q1
    d = float(np.dot(q0, q1))
    if abs(abs(d) - 1.0) < EPS:
        return q0
    if shortestpath and d < 0.0:
        d, q1 = -d, -q1
    angle = math.acos(max(-1.0, min(1.0, d))) + spin * math.pi
    if abs(angle) < EPS:
        return q0
    inverse_sin = 1.0 / math.sin(angle)
    return (math.sin((1.0 - fraction) * angle) * q0 + math.sin(fraction * angle) * q1) * inverse_sin


def random_quaternion(rand: Any = None) -> Array:
    """A unit quaternion drawn uniformly over rotations; ``rand``: three numbers in [0, 1)."""
    u = np.random.random(3) if rand is None else np.asarray(rand, dtype=np.float64)
    if u.shape != (3,):
        raise ValueError(f"random_quaternion takes three numbers in [0, 1); got shape {u.shape}")
    # Shoemake's subgroup algorithm: two angles uniform on the circle, split by sqrt(u0).
    r1, r2 = math.sqrt(1.0 - u[0]), math.sqrt(u[0])
    t1, t2 = 2.0 * math.pi * u[1], 2.0 * math.pi * u[2]
    return np.array([math.sin(t1) * r1, math.cos(t1) * r1, math.sin(t2) * r2, math.cos(t2) * r2])


def random_rotation_matrix(rand: Any = None) -> Array:
    """A rotation drawn uniformly; ``rand``: three numbers in [0, 1) to draw it from."""
    return quaternion_matrix(random_quaternion(rand))
