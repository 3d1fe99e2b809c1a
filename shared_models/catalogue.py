"""Every message package of Skydeck, imported on first need so each type registers its name.

``get_interface`` and ``interface_names`` load the catalogue; a process that only needs a
few types (or none: the CLI's light verbs, the launcher) imports just those modules.
"""

from __future__ import annotations

import importlib

__all__ = ["MESSAGE_PACKAGES", "load_catalogue"]

# One module per ROS package, dependencies first.
MESSAGE_PACKAGES = (
    "builtin_interfaces",
    "std_msgs",
    "geometry_msgs",
    "sensor_msgs",
    "nav_msgs",
    "visualization_msgs",
    "tf2_msgs",
    "rosgraph_msgs",
    "neato2_interfaces",
    "rcl_interfaces",
    "rosapi_msgs",
    "std_srvs",
    "mavros_msgs",
    "ros_workshop",
    "skydeck_launch",
    "skydeck_opencv",
)

_loaded = False


def load_catalogue() -> None:
    """Import every message package (once)."""
    global _loaded
    if not _loaded:
        for package in MESSAGE_PACKAGES:
            importlib.import_module(f"shared_models.{package}")
        _loaded = True
