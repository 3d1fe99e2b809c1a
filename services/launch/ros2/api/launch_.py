"""``launch``: LaunchDescription, and its submodules."""

from services.launch.ros2.actions import LaunchDescription
from services.launch.ros2.api import actions, conditions, sources, substitutions, unprovided
from services.launch.ros2.substitutions import Condition, Substitution

launch_description_sources = sources
__all__ = ["Condition", "LaunchDescription", "Substitution", "actions", "conditions", "launch_description_sources", "substitutions"]
__getattr__ = unprovided("launch", ["LaunchDescription", "actions", "substitutions", "conditions", "launch_description_sources"])
