"""``tf2_geometry_msgs``: a TransformStamped applied to geometry_msgs messages.

    from tf2_geometry_msgs import do_transform_point
    t = self.tf_buffer.lookup_transform('odom', 'base_link', Time())
    point_in_odom = do_transform_point(point_in_base_link, t)

The functions are :mod:`services.ros.tf2_ros.do_transform`'s (``Buffer.transform`` uses them
too, so importing this module is not needed for it, unlike in ROS).
"""

from __future__ import annotations

from services.ros.tf2_ros import do_transform
from services.ros.tf2_ros.do_transform import *  # noqa: F403 (its __all__, listed once there)

__all__ = list(do_transform.__all__)
