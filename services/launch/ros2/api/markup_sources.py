"""``launch_xml.launch_description_sources`` and ``launch_yaml``'s (and the packages themselves)."""

import sys

from services.launch.ros2.actions import LaunchDescriptionSource
from services.launch.ros2.api import unprovided

XMLLaunchDescriptionSource = LaunchDescriptionSource
YAMLLaunchDescriptionSource = LaunchDescriptionSource
launch_description_sources = sys.modules[__name__]  # launch_xml.launch_description_sources

__all__ = ["XMLLaunchDescriptionSource", "YAMLLaunchDescriptionSource", "launch_description_sources"]
__getattr__ = unprovided("launch_xml", __all__)
