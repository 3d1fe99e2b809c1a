"""ROS 2's launch actions that Skydeck provides, as ``launch`` and ``launch_ros`` spell them,
made by a Python launch file's own code or read from an XML or YAML one
(:mod:`services.launch.ros2.markup`), then evaluated (:mod:`services.launch.ros2.evaluate`).

    LaunchDescription([...]), .add_action(a)
    DeclareLaunchArgument(name, default_value=, description=, choices=)
    SetLaunchConfiguration(name, value)                         <let name value>
    IncludeLaunchDescription(PythonLaunchDescriptionSource(path), launch_arguments={...}.items())
    GroupAction([...], scoped=True, launch_configurations={...})
    PushRosNamespace(namespace)                                 (PushROSNamespace too)
    Node(package=, executable=, name=, namespace=, parameters=[{...}, 'params.yaml'],
         remappings=[('from', 'to')], arguments=[...], ros_arguments=[...], output=,
         respawn=, additional_env={...})

Every action takes ``condition=IfCondition(...)``/``UnlessCondition(...)``. A keyword Skydeck
does not provide is one line naming it and the user's line; one that changes nothing here
(``output``, ``emulate_tty``) is accepted.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from services.launch.ros2.places import Place, caller_place
from services.launch.ros2.substitutions import Condition

__all__ = [
    "Action",
    "DeclareLaunchArgument",
    "GroupAction",
    "IncludeLaunchDescription",
    "LaunchDescription",
    "LaunchDescriptionSource",
    "Node",
    "PushRosNamespace",
    "SetLaunchConfiguration",
]

# Keywords of launch's ExecuteProcess that change nothing under Skydeck's supervisor (its output
# goes to the terminal, prefixed, whatever they say).
_HARMLESS = frozenset({"output", "emulate_tty", "log_cmd", "sigterm_timeout", "sigkill_timeout", "respawn_delay"})


class Action:
    """A launch action: where it was written, and its condition."""

    ros_name = "launch.Action"

    def __init__(self, *, condition: Condition | None = None, **unknown: Any) -> None:
        self.place: Place = caller_place()
        for keyword in unknown:
            if keyword not in _HARMLESS:
                raise self.place.error(f"{self.ros_name}({keyword}=...) is not provided by Skydeck")
        if condition is not None and not isinstance(condition, Condition):
            raise self.place.error(f"{self.ros_name}: condition= takes IfCondition(...) or UnlessCondition(...)")
        self.condition = condition


class LaunchDescription:
    """What ``generate_launch_description()`` returns: the actions, in order."""

    def __init__(self, initial_entities: Iterable[Any] | None = None, *, deprecated_reason: str | None = None) -> None:
        self.place = caller_place()
        self.entities: list[Any] = list(initial_entities or [])

    def add_action(self, action: Any) -> None:
        self.entities.append(action)

    def add_entity(self, entity: Any) -> None:
        self.entities.append(entity)

    @property
    def entities_list(self) -> list[Any]:
        return self.entities


class DeclareLaunchArgument(Action):
    ros_name = "launch.actions.DeclareLaunchArgument"

    def __init__(
        self, name: str, *, default_value: Any = None, description: str | None = None,
        choices: Iterable[str] | None = None, **kwargs: Any,
    ) -> None:  # fmt: skip
        super().__init__(**kwargs)
        if not isinstance(name, str) or not name:
            raise self.place.error(f"{self.ros_name}: the name must be text, got {name!r}")
        self.name = name
        self.default_value = default_value
        self.description = description or ""
        self.choices = tuple(choices) if choices is not None else None


class SetLaunchConfiguration(Action):
    ros_name = "launch.actions.SetLaunchConfiguration"

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = name
        self.value = value


class LaunchDescriptionSource:
    """Where an included launch file is: its path (text or substitutions). Its kind (Python,
    XML, YAML) is read from the file when it is included, whichever source class names it."""

    def __init__(self, launch_file_path: Any, *args: Any, **kwargs: Any) -> None:
        self.place = caller_place()
        self.path = launch_file_path


class IncludeLaunchDescription(Action):
    ros_name = "launch.actions.IncludeLaunchDescription"

    def __init__(self, launch_description_source: Any, *, launch_arguments: Iterable[Any] | None = None, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if isinstance(launch_description_source, (str, Path)) or not isinstance(
            launch_description_source, LaunchDescriptionSource
        ):  # newer launch takes a path too
            launch_description_source = _source(launch_description_source, self.place)
        self.source = launch_description_source
        pairs = list(launch_arguments.items() if isinstance(launch_arguments, dict) else launch_arguments or [])
        for pair in pairs:
            if not (isinstance(pair, tuple) and len(pair) == 2):
                raise self.place.error(f"{self.ros_name}: launch_arguments are (name, value) pairs, got {pair!r}")
        self.launch_arguments: list[tuple[Any, Any]] = pairs


def _source(value: Any, place: Place) -> LaunchDescriptionSource:
    source = LaunchDescriptionSource(value)
    source.place = place
    return source


class GroupAction(Action):
    ros_name = "launch.actions.GroupAction"

    def __init__(
        self, actions: Iterable[Any], *, scoped: bool = True, forwarding: bool = True,
        launch_configurations: dict[Any, Any] | None = None, **kwargs: Any,
    ) -> None:  # fmt: skip
        super().__init__(**kwargs)
        self.actions = list(actions)
        self.scoped = scoped
        self.launch_configurations = dict(launch_configurations or {})


class PushRosNamespace(Action):
    ros_name = "launch_ros.actions.PushRosNamespace"

    def __init__(self, namespace: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.namespace = namespace


class Node(Action):
    ros_name = "launch_ros.actions.Node"

    def __init__(
        self, *, executable: Any, package: Any = None, name: Any = None, namespace: Any = None,
        exec_name: Any = None, parameters: Iterable[Any] | None = None,
        remappings: Iterable[tuple[Any, Any]] | None = None, arguments: Iterable[Any] | None = None,
        ros_arguments: Iterable[Any] | None = None, respawn: Any = False,
        additional_env: dict[Any, Any] | None = None, **kwargs: Any,
    ) -> None:  # fmt: skip
        super().__init__(**kwargs)
        if package is None:
            raise self.place.error(f"{self.ros_name}: give package= (Skydeck runs a package's executable, as ros2 run)")
        self.package = package
        self.executable = executable
        self.name = name
        self.namespace = namespace
        self.parameters = list(parameters or [])
        self.remappings = list(remappings or [])
        for pair in self.remappings:
            if not (isinstance(pair, (tuple, list)) and len(pair) == 2):
                raise self.place.error(f"{self.ros_name}: remappings are (from, to) pairs, got {pair!r}")
        self.arguments = list(arguments or [])
        self.ros_arguments = list(ros_arguments or [])
        self.respawn = respawn
        self.additional_env = dict(additional_env or {})
        self.param_places: list[Place] = []  # an XML/YAML <param>'s own line, by index
