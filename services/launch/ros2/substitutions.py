"""ROS 2's substitutions and conditions, as ``launch`` and ``launch_ros`` spell them:
values filled in when the launch runs (:func:`perform`).

    LaunchConfiguration('rate', default='10')      $(var rate)
    TextSubstitution(text='robot')                 plain text
    PathJoinSubstitution([FindPackageShare('pkg'), 'config', 'params.yaml'])
    FindPackageShare('pkg')                        $(find-pkg-share pkg)
    EnvironmentVariable('HOME', default_value='')  $(env HOME '')
    ThisLaunchFileDir()                            $(dirname)
    IfCondition(LaunchConfiguration('sim'))        if="$(var sim)"  (UnlessCondition: unless=)

A value is text, a substitution, or a list of them (joined). Every substitution remembers the
line that made it, and its errors name that line.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

from services.launch.ros2.context import Context
from services.launch.ros2.packages import PackageNotFoundError
from services.launch.ros2.places import Place, caller_place

__all__ = [
    "Condition",
    "EnvironmentVariable",
    "FindPackageShare",
    "IfCondition",
    "LaunchConfiguration",
    "PathJoinSubstitution",
    "Substitution",
    "TextSubstitution",
    "ThisLaunchFileDir",
    "UnlessCondition",
    "perform",
    "truth",
]

_TRUE = ("true", "1", "yes", "on")
_FALSE = ("false", "0", "no", "off")


class Substitution:
    """A value filled in when the launch runs; ``place`` is the line that made it."""

    place: Place

    def __init__(self) -> None:
        self.place = caller_place()

    def perform(self, context: Context) -> str:
        raise NotImplementedError

    def __add__(self, other: object) -> list[Any]:  # `LaunchConfiguration('ns') + '/scan'`
        return [self, other]

    def __radd__(self, other: object) -> list[Any]:
        return [other, self]


def perform(value: Any, context: Context) -> str:
    """``value`` (text, a substitution, a number, or a list of these) as the text it stands for."""
    if isinstance(value, Substitution):
        return value.perform(context)
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple)):
        return "".join(perform(part, context) for part in value)
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, os.PathLike):
        return os.fspath(value)  # type: ignore[no-any-return]
    if isinstance(value, (int, float)):
        return str(value)
    raise caller_place().error(f"{type(value).__name__} is not a substitution Skydeck knows (give text or a substitution)")


def truth(value: Any, context: Context, place: Place) -> bool:
    """A condition's value as ROS reads it: true/1 or false/0 (any case)."""
    text = perform(value, context).strip().lower()
    if text in _TRUE:
        return True
    if text in _FALSE:
        return False
    raise place.error(f"the condition's value {text!r} is not true or false")


class TextSubstitution(Substitution):
    def __init__(self, *, text: str = "") -> None:
        super().__init__()
        self.text = text

    def perform(self, context: Context) -> str:
        return self.text


class LaunchConfiguration(Substitution):
    """A launch argument's (or ``<let>``'s) value; ``default`` if none is set."""

    def __init__(self, variable_name: Any, *, default: Any = None) -> None:
        super().__init__()
        self.variable_name = variable_name
        self.default = default

    def perform(self, context: Context) -> str:
        name = perform(self.variable_name, context)
        if name in context.configurations:
            return context.configurations[name]
        if self.default is not None:
            return perform(self.default, context)
        raise self.place.error(
            f"launch configuration {name!r} is not set: declare it (DeclareLaunchArgument, <arg>) "
            f"or pass {name}:=VALUE"
        )


class PathJoinSubstitution(Substitution):
    def __init__(self, substitutions: Iterable[Any]) -> None:
        super().__init__()
        self.parts = list(substitutions)

    def perform(self, context: Context) -> str:
        return os.path.join(*(perform(part, context) for part in self.parts)) if self.parts else ""


class FindPackageShare(Substitution):
    """The package's share directory (its source folder: :mod:`services.launch.ros2.packages`)."""

    def __init__(self, package: Any) -> None:
        super().__init__()
        self.package = package

    def perform(self, context: Context) -> str:
        name = perform(self.package, context)
        try:
            return str(context.workspace.share_directory(name))
        except PackageNotFoundError as error:
            raise self.place.error(str(error)) from None


class EnvironmentVariable(Substitution):
    def __init__(self, name: Any, *, default_value: Any = None) -> None:
        super().__init__()
        self.name = name
        self.default_value = default_value

    def perform(self, context: Context) -> str:
        name = perform(self.name, context)
        if name in context.environ:
            return context.environ[name]
        if self.default_value is not None:
            return perform(self.default_value, context)
        raise self.place.error(f"the environment variable {name} is not set (give a default)")


class ThisLaunchFileDir(Substitution):
    def perform(self, context: Context) -> str:
        return str(context.file.resolve().parent)


class Condition:
    """``condition=IfCondition(...)``: whether an action runs."""

    def __init__(self, predicate_expression: Any) -> None:
        self.place = caller_place()
        self.expression = predicate_expression

    def evaluate(self, context: Context) -> bool:
        raise NotImplementedError


class IfCondition(Condition):
    def evaluate(self, context: Context) -> bool:
        return truth(self.expression, context, self.place)


class UnlessCondition(Condition):
    def evaluate(self, context: Context) -> bool:
        return not truth(self.expression, context, self.place)
