"""``launch.conditions``."""

from services.launch.ros2.api import unprovided
from services.launch.ros2.substitutions import IfCondition, UnlessCondition

__all__ = ["IfCondition", "UnlessCondition"]
__getattr__ = unprovided("launch.conditions", __all__)
