"""``launch_ros.substitutions``."""

from services.launch.ros2.api import unprovided
from services.launch.ros2.substitutions import FindPackageShare

__all__ = ["FindPackageShare"]
__getattr__ = unprovided("launch_ros.substitutions", __all__)
