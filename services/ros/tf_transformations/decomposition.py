"""A homogeneous matrix as the product of simple parts, and back:

    M = P @ T @ R @ Z @ S

``S`` scales the axes (``scale``), ``Z`` shears (``shear``: x by y, x by z, y by z), ``R``
rotates (``angles``, Euler 'sxyz'), ``T`` translates (``translate``) and ``P`` is the projective
part (``perspective``, the matrix's bottom row; ``[0, 0, 0, 1]`` for a rigid or affine one).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from services.ros.tf_transformations.euler import euler_from_matrix, euler_matrix
from services.ros.tf_transformations.matrices import EPS, Array

__all__ = ["compose_matrix", "decompose_matrix"]


def compose_matrix(
    scale: Any = None, shear: Any = None, angles: Any = None, translate: Any = None, perspective: Any = None
) -> Array:
    """The matrix ``P @ T @ R @ Z @ S`` of the parts given (each part left out is the identity)."""
    matrix = np.identity(4)
    if perspective is not None:
        part = np.identity(4)
        part[3, :] = np.asarray(perspective, dtype=np.float64)[:4]
        matrix = matrix @ part
    if translate is not None:
        part = np.identity(4)
        part[:3, 3] = np.asarray(translate, dtype=np.float64)[:3]
        matrix = matrix @ part
    if angles is not None:
        matrix = matrix @ euler_matrix(angles[0], angles[1], angles[2], "sxyz")
    if shear is not None:
        xy, xz, yz = np.asarray(shear, dtype=np.float64)[:3]
        part = np.identity(4)
        part[0, 1], part[0, 2], part[1, 2] = xy, xz, yz
        matrix = matrix @ part
    if scale is not None:
        matrix = matrix @ np.diag([*np.asarray(scale, dtype=np.float64)[:3], 1.0])
    return matrix / matrix[3, 3]


def decompose_matrix(matrix: Any) -> tuple[Array, Array, Array, Array, Array]:
    """``(scale, shear, angles, translate, perspective)`` of a matrix built by
    :func:`compose_matrix`; ValueError for a singular one."""
    m = np.array(matrix, dtype=np.float64, copy=True)
    if abs(m[3, 3]) < EPS:
        raise ValueError("the matrix's M[3, 3] is zero: not a homogeneous transformation")
    m /= m[3, 3]
    affine = m.copy()
    affine[3, :] = [0.0, 0.0, 0.0, 1.0]
    if abs(np.linalg.det(affine)) < EPS:
        raise ValueError("the matrix is singular: it has no decomposition")
    # The bottom row of M is the perspective row times the affine part.
    perspective = np.array([0.0, 0.0, 0.0, 1.0])
    if np.any(np.abs(m[3, :3]) > EPS):
        perspective = m[3, :] @ np.linalg.inv(affine)
    translate = affine[:3, 3].copy()
    # The linear part is R @ (Z @ S), an orthogonal times an upper triangular matrix: Gram-Schmidt
    # on its columns gives R's columns, the scales (the lengths) and the shears (the projections).
    columns = [affine[:3, i].copy() for i in range(3)]
    scale = np.zeros(3)
    shear = np.zeros(3)
    scale[0] = np.linalg.norm(columns[0])
    columns[0] /= scale[0]
    shear[0] = columns[0] @ columns[1]
    columns[1] -= shear[0] * columns[0]
    scale[1] = np.linalg.norm(columns[1])
    columns[1] /= scale[1]
    shear[0] /= scale[1]
    shear[1] = columns[0] @ columns[2]
    shear[2] = columns[1] @ columns[2]
    columns[2] -= shear[1] * columns[0] + shear[2] * columns[1]
    scale[2] = np.linalg.norm(columns[2])
    columns[2] /= scale[2]
    shear[1:] /= scale[2]
    rotation = np.column_stack(columns)
    if np.linalg.det(rotation) < 0.0:  # a reflection: carried by negative scales, R stays a rotation
        scale, rotation = -scale, -rotation
    angles = np.array(euler_from_matrix(rotation, "sxyz"))
    return scale, shear, angles, translate, perspective
