"""A ROS 2 launch evaluated: its nodes, filled in, and the launch they make for the supervisor.

Each node runs as ``skydeck run PACKAGE EXECUTABLE`` does (a workspace package's console script
or file; ``package='skydeck'`` names a built-in node: ``sim``, ``teleop``...), with ROS 2's
command line as ``ros2 launch`` gives it::

    skydeck run PKG EXE ARGUMENTS... --workspace WS --ros-args -r __node:=NAME -r __ns:=/NS
        -p NAME:=VALUE --params-file FILE -r FROM:=TO ROS_ARGUMENTS...

on base port + 2, + 3, ... in launch order (the core, when this launch starts it, on the base
port), as a roslaunch file's nodes are.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from services.launch.arguments import LaunchArgument
from services.launch.roslaunch import LaunchEntry, ros_launch_spec
from services.launch.spec import LaunchSpec

__all__ = ["BUILTIN_PACKAGE", "LaunchedNode", "Ros2Launch"]

BUILTIN_PACKAGE = "skydeck"
"""``Node(package='skydeck', executable='sim')``: a node that ships with Skydeck."""


@dataclass(frozen=True)
class LaunchedNode:
    """One node as it will run: its program, its ROS arguments, where the launch file says so."""

    package: str
    executable: str
    name: str | None  # None: the name the program gives itself
    namespace: str  # "" or absolute
    arguments: tuple[str, ...]
    ros_arguments: tuple[str, ...]  # -p, --params-file, -r ... as ROS 2 reads them
    env: tuple[tuple[str, str], ...]
    respawn: bool
    place: str

    @property
    def graph_name(self) -> str:
        """The name the launch shows and ``--exclude`` takes: namespace/name (or the executable's)."""
        base = self.name or Path(self.executable).stem
        return f"{self.namespace.strip('/')}/{base}".strip("/")

    def command_arguments(self, workspaces: tuple[Path, ...]) -> tuple[str, ...]:
        """What follows ``skydeck run PACKAGE EXECUTABLE`` (see the module docstring)."""
        words = list(self.arguments)
        if self.package != BUILTIN_PACKAGE:
            for workspace in workspaces:
                words += ["--workspace", str(workspace)]
        ros = []
        if self.name:
            ros += ["-r", f"__node:={self.name}"]
        if self.namespace:
            ros += ["-r", f"__ns:={self.namespace}"]
        ros += self.ros_arguments
        return tuple(words + (["--ros-args", *ros] if ros else []))


@dataclass(frozen=True)
class Ros2Launch:
    """What a ROS 2 launch file (and what it includes) asks for."""

    file: Path
    nodes: tuple[LaunchedNode, ...]
    arguments: dict[str, LaunchArgument]
    warnings: tuple[str, ...]
    workspaces: tuple[Path, ...]
    parameters: tuple[tuple[str, object], ...] = ()  # ROS 2 has no parameter server: always none

    def spec(self, *, start_core: bool) -> LaunchSpec:
        """The launch the supervisor runs: the core first if ``start_core``, then every node."""
        entries: list[LaunchEntry] = []
        taken: set[str] = set()
        for node in self.nodes:
            name = _unique(node.graph_name, taken)
            taken.add(name)
            package = None if node.package == BUILTIN_PACKAGE else node.package
            arguments = node.command_arguments(self.workspaces)
            entries.append(LaunchEntry(name, node.executable, arguments, node.env, node.respawn, node.place, package))
        return ros_launch_spec(self.file, entries, start_core=start_core)


def _unique(name: str, taken: set[str]) -> str:
    """``name``, or ``name-2``, ``name-3``... when nodes share it (two unnamed talkers)."""
    if name not in taken:
        return name
    count = 2
    while f"{name}-{count}" in taken:
        count += 1
    return f"{name}-{count}"
