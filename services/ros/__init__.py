"""ROS code runs unchanged: façades of rclpy (ROS 2) and rospy (ROS 1), and the ROS module names.

    skydeck run my_node.py --ros-args -r scan:=/robot1/scan -p speed:=0.3

``skydeck run`` calls :func:`enable_ros_imports` before it runs a ``.py`` file, so inside that
process ``import rclpy``, ``import rospy`` and ``from geometry_msgs.msg import Twist`` work:

- ``rclpy`` and its submodules are :mod:`services.ros.rclpy`; ``rospy`` is :mod:`services.ros.rospy`.
- every message package of :mod:`shared_models` (``std_msgs``, ``geometry_msgs``, ``sensor_msgs``...)
  has ``.msg`` and ``.srv`` views whose types ARE the ``shared_models`` classes (one type system,
  one JSON on the wire).
- an unknown package, or a ROS API the façades lack, is one clear line (:mod:`services.ros.errors`).

The façades are thin: nodes are the SDK's :class:`services.runtime.Node`, hosted on one
background event loop per process (:mod:`services.ros.bridge`), so blocking ROS code (threads,
``while ok(): rate.sleep()``, blocking service calls) works. Nothing is installed as a top-level
package, so a real ROS installation in the user's own Python is never shadowed.
"""

from __future__ import annotations

import sys

__all__ = ["disable_ros_imports", "enable_ros_imports"]


def enable_ros_imports() -> None:
    """Make ROS's module names importable in this process (idempotent)."""
    from services.ros.imports import RosImportFinder

    if not any(isinstance(finder, RosImportFinder) for finder in sys.meta_path):
        sys.meta_path.insert(0, RosImportFinder())


def disable_ros_imports() -> None:
    """Undo :func:`enable_ros_imports` and forget the ROS-named modules it imported (tests)."""
    from services.ros.imports import FACADES, RosImportFinder, package_names

    sys.meta_path[:] = [f for f in sys.meta_path if not isinstance(f, RosImportFinder)]
    tops = set(FACADES) | package_names()
    for name in [n for n in sys.modules if n.partition(".")[0] in tops]:
        del sys.modules[name]
