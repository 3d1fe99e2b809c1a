"""The modules a ROS 2 Python launch file imports, served under ROS's names while it runs
(:mod:`services.launch.ros2.python_file`): each is a thin list of what Skydeck provides, and any
other name in it is one line naming it and the user's line (:func:`unprovided`).

    launch, launch.actions, launch.substitutions, launch.conditions,
    launch.launch_description_sources, launch_ros, launch_ros.actions, launch_ros.substitutions,
    launch_xml.launch_description_sources, launch_yaml.launch_description_sources,
    ament_index_python, ament_index_python.packages
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from services.launch.ros2.places import not_provided

__all__ = ["MODULES", "unprovided"]

MODULES = {
    "launch": "launch_",
    "launch.actions": "actions",
    "launch.substitutions": "substitutions",
    "launch.conditions": "conditions",
    "launch.launch_description_sources": "sources",
    "launch_ros": "launch_ros",
    "launch_ros.actions": "ros_actions",
    "launch_ros.substitutions": "ros_substitutions",
    "launch_xml": "markup_sources",
    "launch_xml.launch_description_sources": "markup_sources",
    "launch_yaml": "markup_sources",
    "launch_yaml.launch_description_sources": "markup_sources",
    "ament_index_python": "ament",
    "ament_index_python.packages": "ament",
}
"""A ROS module name -> the module of this package that stands for it."""


def unprovided(ros_name: str, provided: list[str]) -> Callable[[str], Any]:
    """A module ``__getattr__``: a name Skydeck lacks is one line at the user's line."""

    def __getattr__(name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(f"module {ros_name!r} has no attribute {name!r}")
        raise not_provided(f"{ros_name}.{name}", provided)

    return __getattr__
