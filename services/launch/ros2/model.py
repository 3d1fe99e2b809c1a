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

from services.launch.arguments import LaunchArgument, literal
from services.launch.errors import LaunchFileError
from services.launch.roslaunch import NODE_PORT_OFFSET
from services.launch.spec import LaunchSpec, NodeSpec

__all__ = ["BUILTIN_PACKAGE", "LaunchedNode", "Ros2Launch"]

BUILTIN_PACKAGE = "skydeck"
"""``Node(package='skydeck', executable='sim')``: a node that ships with Skydeck."""
_READY_TIMEOUT_S = 30.0


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
        nodes = [NodeSpec(name="core", run="core", port_offset=0)] if start_core else []
        taken: dict[str, str] = {}
        for index, node in enumerate(self.nodes):
            name = _unique(node.graph_name, taken)
            if name == "launch" or (start_core and name == "core"):
                raise LaunchFileError(self.file, f"{node.place}: a node named {name} clashes with skydeck launch's own; rename it")
            taken[name] = node.place
            builtin = node.package == BUILTIN_PACKAGE
            nodes.append(
                NodeSpec(
                    name=name,
                    run=node.executable,
                    package=None if builtin else node.package,
                    port_offset=NODE_PORT_OFFSET + index,
                    # Braces in a ROS 2 launch file are text; in a launch spec, placeholders.
                    args=tuple(literal(word) for word in node.command_arguments(self.workspaces)),
                    env={key: literal(value) for key, value in node.env},
                    respawn=node.respawn,
                    ready_timeout_s=_READY_TIMEOUT_S,
                )
            )
        if not nodes:
            raise LaunchFileError(self.file, "the launch file starts no node (and a core already runs)")
        return LaunchSpec(nodes=tuple(nodes))


def _unique(name: str, taken: dict[str, str]) -> str:
    """``name``, or ``name-2``, ``name-3``... when nodes share it (two unnamed talkers)."""
    if name not in taken:
        return name
    count = 2
    while f"{name}-{count}" in taken:
        count += 1
    return f"{name}-{count}"
