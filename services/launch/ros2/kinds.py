"""Which kind of launch file a path is, read from its name and content:

    *.py                                   a ROS 2 Python launch file (generate_launch_description)
    *.xml, *.launch with ROS 2's words     ROS 2 XML: <node exec=...>, $(var), $(find-pkg-share),
      (else *.launch.xml)                  <let>, <push_ros_namespace>
    *.xml, *.launch otherwise              ROS 1 roslaunch XML (services.launch.roslaunch)
    *.yaml whose top is `launch: [...]`    ROS 2 YAML
    *.yaml otherwise                       Skydeck's own launch file (`nodes: [...]`, services.launch.spec)
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Literal

import yaml

from services.launch.errors import LaunchFileError, read_launch_text
from services.launch.ros2.actions import LaunchDescription
from services.launch.ros2.markup import load_markup
from services.launch.ros2.packages import Workspace
from services.launch.ros2.python_file import load_python

__all__ = ["Kind", "load_description", "ros2_kind"]

Kind = Literal["python", "xml", "yaml"]

_ROS2_XML = re.compile(
    r"<node\b[^>]*\sexec\s*=|\$\((var|find-pkg-share|find-pkg-prefix|eval)\s|<let\b|<push[-_]ros[-_]namespace\b"
)
_ROS2_YAML = re.compile(r"^launch:", re.MULTILINE)
_ROS1_XML = re.compile(r"\$\((arg|find)\s|<rosparam\b|<node\b[^>]*\stype\s*=")


def ros2_kind(path: Path) -> Kind | None:
    """The ROS 2 kind of the launch file at ``path``, or None for ROS 1 XML or Skydeck's YAML."""
    name = path.name
    if name.endswith(".py"):
        return "python"
    if name.endswith((".xml", ".launch")):
        text = read_launch_text(path)
        if _ROS2_XML.search(text):
            return "xml"
        if _ROS1_XML.search(text):
            return None
        return "xml" if name.endswith(".launch.xml") else None
    if name.endswith((".yaml", ".yml")):
        text = read_launch_text(path)
        try:
            data = yaml.safe_load(text)
        except yaml.YAMLError:  # the reader of its kind says where the syntax is wrong
            return "yaml" if _ROS2_YAML.search(text) else None
        return "yaml" if isinstance(data, dict) and "launch" in data and "nodes" not in data else None
    return None


def load_description(path: Path, workspace: Workspace) -> LaunchDescription:
    """The launch description in ``path``, whichever of ROS 2's three kinds it is."""
    kind = ros2_kind(path)
    if kind == "python":
        return load_python(path, workspace)
    if kind is not None:
        return load_markup(path, kind)
    raise LaunchFileError(path, "is not a ROS 2 launch file (.launch.py, ROS 2 XML, or YAML with `launch:`)")
