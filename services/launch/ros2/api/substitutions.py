"""``launch.substitutions``."""

from services.launch.ros2.api import unprovided
from services.launch.ros2.substitutions import (
    EnvironmentVariable,
    LaunchConfiguration,
    PathJoinSubstitution,
    Substitution,
    TextSubstitution,
    ThisLaunchFileDir,
)

__all__ = ["EnvironmentVariable", "LaunchConfiguration", "PathJoinSubstitution", "Substitution", "TextSubstitution", "ThisLaunchFileDir"]
__getattr__ = unprovided("launch.substitutions", __all__)
