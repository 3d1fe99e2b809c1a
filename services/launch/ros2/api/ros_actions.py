"""``launch_ros.actions``."""

from services.launch.ros2.actions import Node, PushRosNamespace
from services.launch.ros2.api import unprovided

PushROSNamespace = PushRosNamespace  # the newer spelling

__all__ = ["Node", "PushROSNamespace", "PushRosNamespace"]
__getattr__ = unprovided("launch_ros.actions", __all__)
