"""``launch_ros``: its submodules."""

from services.launch.ros2.api import ros_actions, ros_substitutions, unprovided

actions = ros_actions
substitutions = ros_substitutions
__all__ = ["actions", "substitutions"]
__getattr__ = unprovided("launch_ros", __all__)
