"""``launch.launch_description_sources``: every source names a file; its kind is read from it."""

from services.launch.ros2.actions import LaunchDescriptionSource
from services.launch.ros2.api import unprovided

PythonLaunchDescriptionSource = LaunchDescriptionSource
AnyLaunchDescriptionSource = LaunchDescriptionSource
FrontendLaunchDescriptionSource = LaunchDescriptionSource

__all__ = ["AnyLaunchDescriptionSource", "FrontendLaunchDescriptionSource", "PythonLaunchDescriptionSource"]
__getattr__ = unprovided("launch.launch_description_sources", __all__)
