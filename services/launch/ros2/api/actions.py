"""``launch.actions``."""

from services.launch.ros2.actions import (
    DeclareLaunchArgument,
    GroupAction,
    IncludeLaunchDescription,
    SetLaunchConfiguration,
)
from services.launch.ros2.api import unprovided

__all__ = ["DeclareLaunchArgument", "GroupAction", "IncludeLaunchDescription", "SetLaunchConfiguration"]
__getattr__ = unprovided("launch.actions", __all__)
