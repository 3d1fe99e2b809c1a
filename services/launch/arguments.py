"""Launch arguments: what a launch file declares, what ``name:=value`` gives, and what is filled in.

    # a YAML launch file
    arguments:
      rate:
        default: "30"
        description: the control loop's rate, Hz
      world: {}              # no default: `skydeck launch FILE world:=...` must give it
      fast:
        default: "false"
        choices: ["true", "false"]   # any other value is refused before anything starts
    nodes:
      - {name: control, run: control, port_offset: 3, args: ["--rate", "{rate}"]}

A declared argument is used as ``{name}`` wherever the launch options' placeholders are (a
node's ``args`` and ``env`` values), ROS 2's ``$(var name)`` and roslaunch's ``$(arg name)``.
A roslaunch file declares its own with ``<arg name default doc>``;
:func:`services.launch.run.launch_arguments` lists either kind for ``--show-args``.
"""

from __future__ import annotations

import string
from collections.abc import Mapping
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from services.launch.errors import LaunchError

__all__ = ["LaunchArgument", "fill_arguments", "literal", "show_arguments", "substitute"]

NO_DESCRIPTION = "no description given"


class LaunchArgument(BaseModel):
    """One declared argument: its default (None: it must be given) and what it is for."""

    model_config = ConfigDict(extra="forbid", frozen=True, coerce_numbers_to_str=True)

    default: str | None = Field(default=None, description="the value when none is given; none: required")
    description: str = Field(default="", description="shown by `skydeck launch FILE --show-args`")
    choices: tuple[str, ...] | None = Field(
        default=None, description="the values it may take (ROS 2's DeclareLaunchArgument choices); none: any"
    )

    @field_validator("default", mode="before")
    @classmethod
    def _yaml_boolean(cls, value: Any) -> Any:
        # YAML reads `default: true` as a boolean; the node is given the text a user typed.
        return str(value).lower() if isinstance(value, bool) else value

    @model_validator(mode="after")
    def _default_is_a_choice(self) -> LaunchArgument:
        if self.choices is not None and self.default is not None and self.default not in self.choices:
            raise ValueError(f"default {self.default!r} is not one of its choices ({', '.join(self.choices)})")
        return self

    @field_validator("choices", mode="before")
    @classmethod
    def _yaml_booleans(cls, value: Any) -> Any:
        if isinstance(value, list | tuple):
            return tuple(str(item).lower() if isinstance(item, bool) else item for item in value)
        return value


def fill_arguments(declared: Mapping[str, LaunchArgument], given: Mapping[str, str]) -> dict[str, str]:
    """Each declared argument's value: given, else its default.

    Raises ``LaunchError`` (one line) for a given name that is not declared, a declared
    argument with no default that is not given, or a value outside the argument's choices.
    """
    unknown = [name for name in given if name not in declared]
    if unknown:
        takes = f"it takes {', '.join(declared)}: `--show-args` describes them" if declared else "it declares none"
        raise LaunchError(f"{', '.join(f'{name}:={given[name]}' for name in unknown)}: no such launch argument ({takes})")
    values = {}
    for name, argument in declared.items():
        value = given.get(name, argument.default)
        if value is None:
            raise LaunchError(f"launch argument {name!r} has no default: give it as {name}:=VALUE")
        if argument.choices is not None and value not in argument.choices:
            raise LaunchError(f"{name}:={value}: not one of its choices ({', '.join(argument.choices)})")
        values[name] = value
    return values


def substitute(text: str, values: Mapping[str, str]) -> str:
    """``text`` (a placeholder template) with ``{name}`` replaced for each name of ``values``;
    the other placeholders, and literal braces (``{{``), are left for the launch options."""
    out = []
    for text_before, field, _spec, _conversion in string.Formatter().parse(text):
        out.append(literal(text_before))
        if field is not None:
            out.append(literal(values[field]) if field in values else "{" + field + "}")
    return "".join(out)


def show_arguments(arguments: Mapping[str, LaunchArgument]) -> str:
    """The arguments as ``ros2 launch --show-args`` prints them."""
    if not arguments:
        return "Arguments (pass arguments as '<name>:=<value>'):\n\n  No arguments."
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    for name, argument in arguments.items():
        lines += ["", f"    '{name}':", f"        {argument.description or NO_DESCRIPTION}"]
        if argument.choices is not None:
            lines.append("        Valid choices are: [" + ", ".join(f"'{choice}'" for choice in argument.choices) + "]")
        lines.append("        (required)" if argument.default is None else f"        (default: '{argument.default}')")
    return "\n".join(lines)


def literal(text: str) -> str:
    """``text`` as a placeholder template that stands for itself: its braces doubled."""
    return text.replace("{", "{{").replace("}", "}}")
