"""A rigid transform (translation and unit quaternion ``[x, y, z, w]``) in plain floats: what the
buffer stores, chains and interpolates, and what ``tf2_geometry_msgs`` applies to messages.

Plain tuples rather than numpy: a lookup composes a handful of these, where array overhead
would cost more than the arithmetic.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

__all__ = ["IDENTITY", "Rigid", "quaternion_multiply", "rotate", "slerp"]

Vector = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]


def quaternion_multiply(a: Quaternion, b: Quaternion) -> Quaternion:
    """The Hamilton product ``a b`` (``b`` rotates first)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def rotate(q: Quaternion, v: Vector) -> Vector:
    """``v`` rotated by the unit quaternion ``q``."""
    x, y, z, w = q
    vx, vy, vz = v
    # v' = v + w t + u x t, with u the vector part and t = 2 (u x v)
    tx, ty, tz = 2.0 * (y * vz - z * vy), 2.0 * (z * vx - x * vz), 2.0 * (x * vy - y * vx)
    return (vx + w * tx + y * tz - z * ty, vy + w * ty + z * tx - x * tz, vz + w * tz + x * ty - y * tx)


def slerp(a: Quaternion, b: Quaternion, ratio: float) -> Quaternion:
    """Spherical interpolation from ``a`` (0) to ``b`` (1), the shorter way round."""
    dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    if dot < 0.0:
        b, dot = (-b[0], -b[1], -b[2], -b[3]), -dot
    if dot > 0.9995:  # nearly the same rotation: a normalised lerp is exact enough, and stable
        q = tuple(a[i] + ratio * (b[i] - a[i]) for i in range(4))
        n = math.sqrt(sum(c * c for c in q))
        return (q[0] / n, q[1] / n, q[2] / n, q[3] / n)
    angle = math.acos(dot)
    s = math.sin(angle)
    wa, wb = math.sin((1.0 - ratio) * angle) / s, math.sin(ratio * angle) / s
    return (wa * a[0] + wb * b[0], wa * a[1] + wb * b[1], wa * a[2] + wb * b[2], wa * a[3] + wb * b[3])


class Rigid(NamedTuple):
    """Maps points of a child frame into its parent: ``p_parent = rotation * p_child + translation``."""

    translation: Vector
    rotation: Quaternion

    @classmethod
    def from_msg(cls, transform: Any) -> Rigid:
        """From a ``geometry_msgs/Transform`` (or anything with ``translation`` and ``rotation``)."""
        t, r = transform.translation, transform.rotation
        return cls((t.x, t.y, t.z), (r.x, r.y, r.z, r.w))

    def then(self, outer: Rigid) -> Rigid:
        """This transform followed by ``outer`` (child -> parent -> grandparent)."""
        tx, ty, tz = rotate(outer.rotation, self.translation)
        ox, oy, oz = outer.translation
        return Rigid((tx + ox, ty + oy, tz + oz), quaternion_multiply(outer.rotation, self.rotation))

    def inverse(self) -> Rigid:
        x, y, z, w = self.rotation
        conjugate = (-x, -y, -z, w)
        tx, ty, tz = rotate(conjugate, self.translation)
        return Rigid((-tx, -ty, -tz), conjugate)

    def apply(self, point: Vector) -> Vector:
        """A point of the child frame, in the parent frame."""
        x, y, z = rotate(self.rotation, point)
        tx, ty, tz = self.translation
        return (x + tx, y + ty, z + tz)

    def interpolate(self, later: Rigid, ratio: float) -> Rigid:
        """Between this (0) and ``later`` (1): translation linearly, rotation by slerp."""
        a, b = self.translation, later.translation
        translation = (a[0] + ratio * (b[0] - a[0]), a[1] + ratio * (b[1] - a[1]), a[2] + ratio * (b[2] - a[2]))
        return Rigid(translation, slerp(self.rotation, later.rotation, ratio))


IDENTITY = Rigid((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
