"""``tf_transformations`` (ROS 2) and ``tf.transformations`` (ROS 1): rotations, quaternions and
homogeneous matrices with numpy, as ROS programs call them.

    from tf_transformations import euler_from_quaternion, quaternion_from_euler
    roll, pitch, yaw = euler_from_quaternion([q.x, q.y, q.z, q.w])
    x, y, z, w = quaternion_from_euler(0.0, 0.0, yaw)

Quaternions are ``[x, y, z, w]`` (ROS's order), matrices 4x4 homogeneous, angles radians, and
Euler conventions the 24 ``axes`` strings (``'sxyz'`` by default: :mod:`.euler`). Written from
the mathematics, one module per kind: :mod:`.matrices`, :mod:`.quaternions`, :mod:`.euler`,
:mod:`.decomposition`. The rarer functions of the original (projections, arcballs, ...) name
themselves as not provided.
"""

from __future__ import annotations

from services.ros.errors import not_provided_attributes
from services.ros.tf_transformations.decomposition import compose_matrix, decompose_matrix
from services.ros.tf_transformations.euler import (
    euler_from_matrix,
    euler_from_quaternion,
    euler_matrix,
    quaternion_from_euler,
)
from services.ros.tf_transformations.matrices import (
    concatenate_matrices,
    identity_matrix,
    inverse_matrix,
    is_same_transform,
    random_vector,
    rotation_from_matrix,
    rotation_matrix,
    scale_matrix,
    translation_from_matrix,
    translation_matrix,
    unit_vector,
    vector_norm,
)
from services.ros.tf_transformations.quaternions import (
    quaternion_about_axis,
    quaternion_conjugate,
    quaternion_from_matrix,
    quaternion_imag,
    quaternion_inverse,
    quaternion_matrix,
    quaternion_multiply,
    quaternion_real,
    quaternion_slerp,
    random_quaternion,
    random_rotation_matrix,
)

__all__ = [
    "compose_matrix",
    "concatenate_matrices",
    "decompose_matrix",
    "euler_from_matrix",
    "euler_from_quaternion",
    "euler_matrix",
    "identity_matrix",
    "inverse_matrix",
    "is_same_transform",
    "quaternion_about_axis",
    "quaternion_conjugate",
    "quaternion_from_euler",
    "quaternion_from_matrix",
    "quaternion_imag",
    "quaternion_inverse",
    "quaternion_matrix",
    "quaternion_multiply",
    "quaternion_real",
    "quaternion_slerp",
    "random_quaternion",
    "random_rotation_matrix",
    "random_vector",
    "rotation_from_matrix",
    "rotation_matrix",
    "scale_matrix",
    "translation_from_matrix",
    "translation_matrix",
    "unit_vector",
    "vector_norm",
]

_NOT_PROVIDED = frozenset(
    {
        "Arcball",
        "arcball_constrain_to_axis",
        "arcball_map_to_sphere",
        "arcball_nearest_axis",
        "clip_matrix",
        "orthogonalization_matrix",
        "projection_from_matrix",
        "projection_matrix",
        "reflection_from_matrix",
        "reflection_matrix",
        "scale_from_matrix",
        "shear_from_matrix",
        "shear_matrix",
        "superimposition_matrix",
    }
)


__getattr__ = not_provided_attributes("tf_transformations", _NOT_PROVIDED)
