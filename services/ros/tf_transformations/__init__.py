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
from services.ros.tf_transformations import decomposition, euler, matrices, quaternions

# One list of names per module, in its __all__.
from services.ros.tf_transformations.decomposition import *  # noqa: F403
from services.ros.tf_transformations.euler import *  # noqa: F403
from services.ros.tf_transformations.matrices import *  # noqa: F403
from services.ros.tf_transformations.quaternions import *  # noqa: F403

__all__ = sorted({*decomposition.__all__, *euler.__all__, *matrices.__all__, *quaternions.__all__})

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
