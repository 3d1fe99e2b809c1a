"""Evaluating a ROS 2 launch description as ``ros2 launch`` does, in order: arguments take
their values, conditions decide, groups scope, namespaces push, includes read their file, and
each ``Node`` becomes a :class:`~services.launch.ros2.model.LaunchedNode`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml

from services.builtin_nodes import BUILTIN_NODES
from services.launch.arguments import LaunchArgument
from services.launch.ros2.actions import (
    Action,
    DeclareLaunchArgument,
    GroupAction,
    IncludeLaunchDescription,
    LaunchDescription,
    Node,
    PushRosNamespace,
    SetLaunchConfiguration,
)
from services.launch.ros2.context import Context
from services.launch.ros2.kinds import load_description
from services.launch.ros2.model import BUILTIN_PACKAGE, LaunchedNode
from services.launch.ros2.packages import PackageNotFoundError
from services.launch.ros2.places import Place
from services.launch.ros2.substitutions import Substitution, perform, truth
from services.ros.setup_files import SetupFileError, console_scripts

__all__ = ["evaluate_file"]

_MAX_INCLUDE_DEPTH = 16


def evaluate_file(path: Path, context: Context, nodes: list[LaunchedNode]) -> None:
    """Read the launch file at ``path`` (any of the three kinds) and evaluate it into ``nodes``."""
    _evaluate(load_description(path, context.workspace), context, nodes)


def _evaluate(entity: Any, context: Context, nodes: list[LaunchedNode]) -> None:
    if isinstance(entity, LaunchDescription):
        for inner in entity.entities:
            _evaluate(inner, context, nodes)
        return
    if isinstance(entity, (list, tuple)):
        for inner in entity:
            _evaluate(inner, context, nodes)
        return
    if not isinstance(entity, Action):
        raise Place(context.file).error(
            f"{type(entity).__name__} is not a launch action Skydeck provides (a LaunchDescription holds "
            "Node, DeclareLaunchArgument, IncludeLaunchDescription, GroupAction, PushRosNamespace...)"
        )
    if entity.condition is not None and not entity.condition.evaluate(context):
        return
    if isinstance(entity, DeclareLaunchArgument):
        _declare(entity, context)
    elif isinstance(entity, SetLaunchConfiguration):
        context.configurations[perform(entity.name, context)] = perform(entity.value, context)
    elif isinstance(entity, PushRosNamespace):
        context.namespace = _namespace(context.namespace, perform(entity.namespace, context), entity.place)
    elif isinstance(entity, GroupAction):
        inner = context.scoped() if entity.scoped else context
        for key, value in entity.launch_configurations.items():
            inner.configurations[perform(key, context)] = perform(value, context)
        _evaluate(entity.actions, inner, nodes)
    elif isinstance(entity, IncludeLaunchDescription):
        _include(entity, context, nodes)
    elif isinstance(entity, Node):
        nodes.append(_node(entity, context))
    else:  # an Action subclass of the user's own
        raise entity.place.error(f"{type(entity).__name__} is not a launch action Skydeck provides")


def _declare(action: DeclareLaunchArgument, context: Context) -> None:
    default = None if action.default_value is None else perform(action.default_value, context)
    context.declared.arguments.setdefault(
        action.name, LaunchArgument(default=default, description=action.description, choices=action.choices)
    )
    if action.name not in context.configurations:
        if default is None and not context.listing:
            raise action.place.error(f"the launch argument {action.name!r} has no default: pass {action.name}:=VALUE")
        context.configurations[action.name] = default or ""
    value = context.configurations[action.name]
    if action.choices is not None and context.listing and not value:
        return
    if action.choices is not None and value not in action.choices:
        raise action.place.error(
            f"the launch argument {action.name}:={value} is not one of its choices ({', '.join(action.choices)})"
        )


def _include(action: IncludeLaunchDescription, context: Context, nodes: list[LaunchedNode]) -> None:
    text = perform(action.source.path, context)
    path = Path(text) if os.path.isabs(text) else context.file.resolve().parent / text
    if not path.is_file():
        raise action.place.error(f"the included launch file {text} does not exist")
    if context.depth >= _MAX_INCLUDE_DEPTH:
        raise action.place.error(f"includes nest deeper than {_MAX_INCLUDE_DEPTH} files (does a file include itself?)")
    given = {perform(name, context): perform(value, context) for name, value in action.launch_arguments}
    inner = context.scoped(file=path)
    inner.configurations.update(given)
    evaluate_file(path, inner, nodes)


def _namespace(outer: str, namespace: str, place: Place) -> str:
    """ROS 2's rule: a relative namespace goes under the pushed one, an absolute one replaces it."""
    namespace = namespace.strip()
    joined = namespace if namespace.startswith("/") else f"{outer}/{namespace}"
    parts = [part for part in joined.split("/") if part]
    for part in parts:
        if not (part[0].isalpha() or part[0] == "_") or not all(c.isalnum() or c == "_" for c in part):
            raise place.error(f"namespace {namespace!r}: {part!r} is not a valid ROS name part (letters, digits, _)")
    return "/" + "/".join(parts) if parts else ""


def _node(node: Node, context: Context) -> LaunchedNode:
    package = perform(node.package, context)
    executable = perform(node.executable, context)
    if package == BUILTIN_PACKAGE and executable not in BUILTIN_NODES:
        raise node.place.error(f"Skydeck has no built-in node {executable!r}; its nodes: {', '.join(BUILTIN_NODES)}")
    if package != BUILTIN_PACKAGE and not context.listing:
        _check_executable(package, executable, context, node.place)
    namespace = context.namespace
    if node.namespace is not None:
        namespace = _namespace(context.namespace, perform(node.namespace, context), node.place)
    ros: list[str] = []
    for index, parameters in enumerate(node.parameters):
        place = node.param_places[index] if index < len(node.param_places) else node.place
        ros += _parameters(parameters, context, place)
    for source, target in node.remappings:
        ros += ["-r", f"{perform(source, context)}:={perform(target, context)}"]
    ros += [perform(word, context) for word in node.ros_arguments]
    respawn = node.respawn if isinstance(node.respawn, bool) else truth(node.respawn, context, node.place)
    return LaunchedNode(
        package=package,
        executable=executable,
        name=None if node.name is None else perform(node.name, context),
        namespace=namespace,
        arguments=tuple(perform(word, context) for word in node.arguments),
        ros_arguments=tuple(ros),
        env=tuple((perform(key, context), perform(value, context)) for key, value in node.additional_env.items()),
        respawn=respawn,
        place=str(node.place),
    )


def _check_executable(package: str, executable: str, context: Context, place: Place) -> None:
    """One line now for a package or console script that is not there, before anything starts."""
    try:
        folder = context.workspace.share_directory(package)
        scripts = console_scripts(folder)
    except (PackageNotFoundError, SetupFileError) as error:
        raise place.error(str(error)) from None
    if scripts and executable not in scripts and not executable.endswith(".py"):
        raise place.error(f"package {package} has no executable {executable!r}; its entry points: {', '.join(sorted(scripts))}")


def _parameters(value: Any, context: Context, place: Place) -> list[str]:
    """One entry of ``parameters=``: a dict (``-p NAME:=VALUE`` each) or a params file."""
    if isinstance(value, Mapping):
        words: list[str] = []
        for name, item in _flattened(value, "", context):
            words += ["-p", f"{name}:={_parameter_text(item, context)}"]
        return words
    path = Path(perform(value, context))
    if not path.is_file():
        raise place.error(f"the parameters file {path} does not exist")
    return ["--params-file", str(path.resolve())]


def _flattened(mapping: Mapping[Any, Any], prefix: str, context: Context) -> list[tuple[str, Any]]:
    """Nested dicts as ROS 2 names them: ``{'gains': {'p': 1}}`` is ``gains.p``."""
    items: list[tuple[str, Any]] = []
    for key, item in mapping.items():
        name = prefix + perform(key, context)
        if isinstance(item, Mapping):
            items += _flattened(item, f"{name}.", context)
        else:
            items.append((name, item))
    return items


def _parameter_text(value: Any, context: Context) -> str:
    """A value as ``-p`` takes it: a substitution's text as written (ROS reads it as YAML), a
    Python value as YAML that reads back as the same value (``'1'`` stays text)."""
    if isinstance(value, Substitution) or (isinstance(value, (list, tuple)) and any(isinstance(v, Substitution) for v in value)):
        return perform(value, context)
    text = yaml.safe_dump(value, default_flow_style=True, width=2**31)
    return text.removesuffix("...\n").strip()
