"""4x4 homogeneous matrices: identity, translation, rotation about an axis, scaling, products,
inverses, and the vector helpers the rest is built on.

A point ``p`` (a column ``[x, y, z, 1]``) is moved by ``M @ p``; ``concatenate_matrices(A, B)``
is ``A @ B``, so ``B`` acts first. Every function takes anything ``numpy.asarray`` reads and
returns new ``float64`` arrays.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "EPS",
    "concatenate_matrices",
    "identity_matrix",
    "inverse_matrix",
    "is_same_transform",
    "random_vector",
    "rotation_from_matrix",
    "rotation_matrix",
    "scale_matrix",
    "translation_from_matrix",
    "translation_matrix",
    "unit_vector",
    "vector_norm",
]

Array = NDArray[np.float64]

EPS = np.finfo(float).eps * 4.0
"""Below this a length or an angle's sine counts as zero."""


def identity_matrix() -> Array:
    """The 4x4 identity."""
    return np.identity(4)


def translation_matrix(direction: Any) -> Array:
    """The matrix that moves points by ``direction`` (x, y, z)."""
    matrix = np.identity(4)
    matrix[:3, 3] = np.asarray(direction, dtype=np.float64)[:3]
    return matrix


def translation_from_matrix(matrix: Any) -> Array:
    """The translation (x, y, z) of a homogeneous matrix."""
    return np.array(matrix, dtype=np.float64, copy=True)[:3, 3].copy()


def vector_norm(data: Any, axis: int | None = None, out: Array | None = None) -> Any:
    """Euclidean length of ``data`` (along ``axis``, or of the whole array)."""
    data = np.asarray(data, dtype=np.float64)
    if out is None:
        if data.ndim == 1 or axis is None:
            return math.sqrt(float(np.dot(data.ravel(), data.ravel())))
        return np.sqrt(np.sum(data * data, axis=axis))
    np.sqrt(np.sum(data * data, axis=axis), out=out)
    return None


def unit_vector(data: Any, axis: int | None = None, out: Array | None = None) -> Array | None:
    """``data`` divided by its length (along ``axis``); a zero vector stays zero."""
    data = np.array(data, dtype=np.float64, copy=True)
    if axis is None or data.ndim == 1:
        length = math.sqrt(float(np.dot(data.ravel(), data.ravel())))
        result = data / length if length > 0.0 else data
    else:
        lengths = np.sqrt(np.sum(data * data, axis=axis, keepdims=True))
        result = np.divide(data, lengths, out=np.zeros_like(data), where=lengths > 0.0)
    if out is None:
        return result
    out[...] = result
    return None


def random_vector(size: int) -> Array:
    """``size`` numbers drawn uniformly from [0, 1)."""
    return np.random.random(size)


def rotation_matrix(angle: float, direction: Any, point: Any = None) -> Array:
    """Rotation by ``angle`` (radians, right hand) about the axis ``direction`` through ``point``
    (the origin if None)."""
    axis = np.asarray(unit_vector(np.asarray(direction, dtype=np.float64)[:3]))
    sin, cos = math.sin(angle), math.cos(angle)
    # Rodrigues: R = cos I + sin [u]x + (1 - cos) u u^T
    cross = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    rotation = cos * np.identity(3) + sin * cross + (1.0 - cos) * np.outer(axis, axis)
    matrix = np.identity(4)
    matrix[:3, :3] = rotation
    if point is not None:
        # Move the point to the origin, rotate, move back: t = p - R p.
        p = np.asarray(point, dtype=np.float64)[:3]
        matrix[:3, 3] = p - rotation @ p
    return matrix


def rotation_from_matrix(matrix: Any) -> tuple[float, Array, Array]:
    """``(angle, direction, point)`` of a rotation matrix (the inverse of :func:`rotation_matrix`)."""
    m = np.asarray(matrix, dtype=np.float64)
    rotation = m[:3, :3]
    # The axis is the eigenvector of R for eigenvalue 1.
    values, vectors = np.linalg.eig(rotation)
    found = np.where(abs(np.real(values) - 1.0) < 1e-8)[0]
    if not len(found):
        raise ValueError("not a rotation matrix: no eigenvector for eigenvalue 1")
    direction = np.real(vectors[:, found[-1]]).squeeze()
    # A point on the axis is an eigenvector of M for eigenvalue 1 (its w not zero).
    values, vectors = np.linalg.eig(m)
    found = np.where(abs(np.real(values) - 1.0) < 1e-8)[0]
    if not len(found):
        raise ValueError("not a rotation matrix: no point stays fixed")
    point = np.real(vectors[:, found[-1]]).squeeze()
    point = point / point[3]
    # The angle from the trace (its cosine) and from the skew part along the axis (its sine).
    cosa = (np.trace(rotation) - 1.0) / 2.0
    if abs(direction[2]) > 1e-8:
        sina = (m[1, 0] + (cosa - 1.0) * direction[0] * direction[1]) / direction[2]
    elif abs(direction[1]) > 1e-8:
        sina = (m[0, 2] + (cosa - 1.0) * direction[0] * direction[2]) / direction[1]
    else:
        sina = (m[2, 1] + (cosa - 1.0) * direction[1] * direction[2]) / direction[0]
    return math.atan2(sina, cosa), direction, point


def scale_matrix(factor: float, origin: Any = None, direction: Any = None) -> Array:
    """Scaling by ``factor`` about ``origin``, in every direction or along ``direction`` only."""
    if direction is None:
        matrix = np.diag([factor, factor, factor, 1.0])
        if origin is not None:
            matrix[:3, 3] = np.asarray(origin, dtype=np.float64)[:3] * (1.0 - factor)
        return matrix
    axis = np.asarray(unit_vector(np.asarray(direction, dtype=np.float64)[:3]))
    matrix = np.identity(4)
    matrix[:3, :3] -= (1.0 - factor) * np.outer(axis, axis)
    if origin is not None:
        matrix[:3, 3] = ((1.0 - factor) * np.dot(np.asarray(origin, dtype=np.float64)[:3], axis)) * axis
    return matrix


def concatenate_matrices(*matrices: Any) -> Array:
    """The product of the matrices, left to right (the last acts first)."""
    result = np.identity(4)
    for matrix in matrices:
        result = result @ np.asarray(matrix, dtype=np.float64)
    return result


def inverse_matrix(matrix: Any) -> Array:
    """The inverse of a square matrix."""
    return np.linalg.inv(np.asarray(matrix, dtype=np.float64))


def is_same_transform(matrix0: Any, matrix1: Any) -> bool:
    """Whether two homogeneous matrices are the same transformation (each scaled by its w)."""
    m0 = np.array(matrix0, dtype=np.float64, copy=True)
    m1 = np.array(matrix1, dtype=np.float64, copy=True)
    m0 /= m0[3, 3]
    m1 /= m1[3, 3]
    return bool(np.allclose(m0, m1))
