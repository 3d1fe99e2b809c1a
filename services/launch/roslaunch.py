"""roslaunch XML files: ``skydeck launch path/to/nodes.launch [name:=value ...]`` (``roslaunch``).

    <launch>
      <arg name="use_sim_time" default="true"/>
      <param name="/use_sim_time" value="$(arg use_sim_time)"/>
      <group ns="robot1">
        <remap from="scan" to="base_scan"/>
        <node name="perception" pkg="ros_workshop" type="perception.py" output="screen" args="--fast">
          <param name="rate" value="10"/>          <!-- private: /robot1/perception/rate -->
        </node>
      </group>
      <include file="$(find ros_workshop)/launch/more.launch"><arg name="x" value="1"/></include>
    </launch>

Read here: ``<launch>``, ``<node>`` (name, pkg, type, args, ns, respawn, output; its ``<param>``,
``<rosparam>``, ``<remap>``, ``<env>``), ``<param>`` (value, type, textfile), ``<rosparam>``
(inline YAML or ``command="load" file=``, ``param``, ``ns``, ``subst_value``), ``<arg>`` (default,
value; ``name:=value`` on the command line or in an ``<include>``), ``<remap>``, ``<env>``,
``<group ns>``, ``<include file ns pass_all_args>``, ``if``/``unless`` on every tag, and the
substitutions ``$(arg)``, ``$(find)``, ``$(env)``, ``$(optenv)``, ``$(dirname)``, ``$(anon)``.
A node's ``type`` is a Python file of its package (:mod:`services.launch.ros_packages`).

Read by :func:`services.launch.roslaunch_reader.load_roslaunch_file`. What it becomes (:meth:`RosLaunch.spec`): one launch for the supervisor that runs YAML launch
files, each node ``skydeck run FILE.py`` with ROS 1's arguments as roslaunch passes them
(``__name:=``, ``__ns:=``, ``from:=to``), on base port + 2, + 3, ... in file order (the core,
when this launch starts it, on the base port); and the parameters, which the supervisor sets on
the core's parameter server before it starts a node. Every error is one line naming the file and
the line; an attribute Skydeck does not use is a warning, a tag it does not know an error.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from services.launch.arguments import literal
from services.launch.errors import LaunchFileError
from services.launch.spec import LaunchSpec, NodeSpec

__all__ = ["NODE_PORT_OFFSET", "LaunchEntry", "RosLaunch", "RosNode", "is_roslaunch_file", "ros_launch_spec"]

NODE_PORT_OFFSET = 2
"""The first node's port is the base port + this (+1 is the simulator's, as in the workshop's)."""
_READY_TIMEOUT_S = 30.0
_SUFFIXES = (".launch", ".xml")


def is_roslaunch_file(path: Path) -> bool:
    """Whether ``path`` is a roslaunch XML file (``.launch`` or ``.xml``) rather than a YAML launch."""
    return path.suffix in _SUFFIXES


@dataclass(frozen=True)
class RosNode:
    """One ``<node>``: its graph name, its program and what the program is given."""

    name: str
    program: Path
    args: tuple[str, ...]
    env: tuple[tuple[str, str], ...]
    respawn: bool
    place: str

    @property
    def launch_name(self) -> str:
        """The name the launch shows and ``--exclude`` takes: the graph name without its first ``/``."""
        return self.name.lstrip("/")


@dataclass(frozen=True)
class RosLaunch:
    """What a roslaunch file asks for: its nodes, its parameters (absolute names, in file order)
    and the warnings about what it says that Skydeck does not use."""

    file: Path
    nodes: tuple[RosNode, ...]
    parameters: tuple[tuple[str, Any], ...]
    warnings: tuple[str, ...]

    def spec(self, *, start_core: bool) -> LaunchSpec:
        """The launch the supervisor runs: the core first if ``start_core``, then every node."""
        entries = [
            LaunchEntry(node.launch_name, str(node.program), node.args, node.env, node.respawn, node.place, graph_name=node.name)
            for node in self.nodes
        ]
        return ros_launch_spec(self.file, entries, start_core=start_core)


@dataclass(frozen=True)
class LaunchEntry:
    """One node of a ROS launch file (1 or 2) as the supervisor will run it: ``skydeck run RUN
    ARGS`` (``skydeck run PACKAGE RUN ARGS`` with a package), named ``name`` in the launch."""

    name: str
    run: str
    args: tuple[str, ...]
    env: tuple[tuple[str, str], ...]
    respawn: bool
    place: str
    package: str | None = None
    graph_name: str = ""  # how errors name it, if not by ``name``


def ros_launch_spec(file: Path, entries: list[LaunchEntry], *, start_core: bool) -> LaunchSpec:
    """The launch of a ROS launch file's nodes: the core first if ``start_core``, then each on
    base port + NODE_PORT_OFFSET + its index."""
    nodes = [NodeSpec(name="core", run="core", port_offset=0)] if start_core else []
    for index, entry in enumerate(entries):
        if entry.name == "launch" or (start_core and entry.name == "core"):
            raise LaunchFileError(file, f"{entry.place}: a node named {entry.graph_name or entry.name} clashes with skydeck launch's own; rename it")
        nodes.append(
            NodeSpec(
                name=entry.name,
                package=entry.package,
                run=entry.run,
                port_offset=NODE_PORT_OFFSET + index,
                # Braces in a ROS launch file are text; in a launch spec, placeholders.
                args=tuple(literal(arg) for arg in entry.args),
                env={key: literal(value) for key, value in entry.env},
                respawn=entry.respawn,
                ready_timeout_s=_READY_TIMEOUT_S,
            )
        )
    if not nodes:
        raise LaunchFileError(file, "the launch file starts no node (and a core already runs)")
    return LaunchSpec(nodes=tuple(nodes))
