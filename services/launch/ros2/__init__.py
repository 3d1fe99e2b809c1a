"""ROS 2 launch files under ``skydeck launch``: Python (``*.launch.py``), XML and YAML.

    skydeck launch my_pkg talker.launch.py rate:=5     the package's launch/ folder, as ros2 launch
    skydeck launch src/my_pkg/launch/talker.launch.xml

The file is read (Python: :mod:`~services.launch.ros2.python_file` against Skydeck's ``launch``
modules, :mod:`~services.launch.ros2.api`; XML and YAML: :mod:`~services.launch.ros2.markup`)
into actions (:mod:`~services.launch.ros2.actions`), evaluated
(:mod:`~services.launch.ros2.evaluate`) into nodes, and those become one launch for the
supervisor that runs every launch (:class:`~services.launch.ros2.model.Ros2Launch`). Which kind a
file is: :mod:`~services.launch.ros2.kinds`.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from services.launch.arguments import LaunchArgument
from services.launch.errors import LaunchFileError
from services.launch.ros2.context import Context
from services.launch.ros2.evaluate import evaluate_file
from services.launch.ros2.kinds import ros2_kind
from services.launch.ros2.model import LaunchedNode, Ros2Launch
from services.launch.ros2.packages import Workspace, find_launch_file_in_package
from services.launch.ros_packages import package_of

__all__ = ["Ros2Launch", "declared_ros2_arguments", "find_launch_file_in_package", "load_ros2_launch", "ros2_kind", "workspace_for"]


def workspace_for(path: Path | None, cwd: Path | None = None) -> Workspace:
    """The packages a launch sees: those beside the file's own package, and the current folder's."""
    roots = []
    if path is not None and (package := package_of(path)) is not None:
        roots.append(package.folder.parent)
    roots.append(cwd or Path.cwd())
    return Workspace(roots)


def load_ros2_launch(
    path: Path, launch_args: Mapping[str, str] | None = None, *, environ: Mapping[str, str], cwd: Path | None = None
) -> Ros2Launch:
    """Read and evaluate the ROS 2 launch file at ``path`` with the command line's
    ``name:=value`` arguments. Raises ``LaunchFileError`` with one line naming file and line."""
    given = dict(launch_args or {})
    context = Context(file=path, workspace=workspace_for(path, cwd), environ=environ, configurations=dict(given))
    nodes: list[LaunchedNode] = []
    evaluate_file(path, context, nodes)
    declared = context.declared.arguments
    for name in given:
        if name not in declared:
            known = ", ".join(declared) or "none"
            raise LaunchFileError(path, f"{name}:={given[name]}: the launch declares no argument {name!r} (it declares: {known})")
    return Ros2Launch(
        file=path, nodes=tuple(nodes), arguments=dict(declared), warnings=tuple(context.declared.warnings),
        workspaces=tuple(context.workspace.roots),
    )  # fmt: skip


def declared_ros2_arguments(path: Path, *, environ: Mapping[str, str]) -> dict[str, LaunchArgument]:
    """The arguments the launch declares, its includes' too (``--show-args``), in order; a
    required one is taken as empty while they are listed."""
    context = Context(file=path, workspace=workspace_for(path), environ=environ, listing=True)
    evaluate_file(path, context, [])
    return dict(context.declared.arguments)
