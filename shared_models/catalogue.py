"""Every message package of Skydeck, imported on first need so each type registers its name.

Two kinds: the packages declared in Python (``MESSAGE_PACKAGES``, one module each:
``shared_models/geometry_msgs.py``), and the packages of definition files Skydeck ships
(``shared_models/packages/*``: the tutorials' ``example_interfaces``, ``turtlesim``..., and what
actions need), read by the loader that reads a student's own (``shared_models/definitions/``).

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
    """Import every message package declared in Python (once); :func:`shared_models.all_interfaces`
    also loads the shipped definition packages."""
    global _loaded
    if not _loaded:
        for package in MESSAGE_PACKAGES:
            importlib.import_module(f"shared_models.{package}")
        _loaded = True
