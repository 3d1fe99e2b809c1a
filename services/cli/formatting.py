"""How the CLI prints messages (YAML, as rostopic echo does) and reads DATA (YAML or JSON)."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import yaml

from services.cli.errors import CliError
from shared_models.text_files import parse_yaml

__all__ = ["message_from", "message_view", "parse_data", "system_name", "to_csv", "to_yaml"]

# The systems a bridge's foreign participants belong to (the graph's ``system``), as people say them.
_SYSTEMS = {"ros2": "ROS 2"}


def system_name(system: str) -> str:
    """A foreign participant's system as people name it (``ros2`` -> ``ROS 2``)."""
    return _SYSTEMS.get(system, system)


def to_yaml(value: Any) -> str:
    """A message as block YAML, keys in field order."""
    text = yaml.safe_dump(value, sort_keys=False, default_flow_style=False, allow_unicode=True).rstrip("\n")
    return text.removesuffix("\n...")  # a lone scalar (echo --field x) ends with YAML's document end


def parse_data(text: str | None) -> dict[str, Any]:
    """DATA as given on the command line: YAML or JSON (``"{x: 1.0, y: 2.0}"``); empty is ``{}``."""
    if text is None or not text.strip():
        return {}
    value = parse_yaml(text, lambda reason: CliError(f"DATA is not valid YAML or JSON ({reason}): {text!r}"))
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise CliError(f"DATA must be a mapping of fields such as \"{{x: 1.0, y: 2.0}}\", got {text!r}")
    return value


def message_from(text: str | None, msg_type: Any) -> Any:
    """DATA (YAML or JSON) as a ``msg_type`` message; CliError naming the first bad field."""
    from pydantic import ValidationError

    from services.runtime.edge.frames import describe_validation_error

    try:
        return msg_type.model_validate(parse_data(text))
    except ValidationError as error:
        raise CliError(describe_validation_error(msg_type.__ros_type__, error)) from None


_STEP = re.compile(r"([^.\[\]]+)|\[(\d+)\]")


def message_view(*, field: str | None, no_arr: bool) -> Callable[[Any], Any] | None:
    """What ``topic echo --field PATH --no-arr`` shows of a message; None to show it whole.

    PATH is dotted, with list items by index: ``pose.position``, ``ranges[0]`` or ``ranges.0``.
    A PATH the message does not have raises CliError naming the first step that is missing.
    """
    if field is None and not no_arr:
        return None
    steps: list[str | int] = []
    if field is not None:
        for match in _STEP.finditer(field):
            name, index = match.groups()
            steps.append(int(name) if name is not None and name.isdigit() else name if name is not None else int(index))
        if not steps:
            raise CliError(f"--field {field!r} names no field: give a path such as pose.position.x")

    def show(value: Any) -> Any:
        for depth, step in enumerate(steps):
            try:
                value = value[step]
            except (KeyError, IndexError, TypeError):
                where = ".".join(str(s) for s in steps[: depth + 1])
                raise CliError(f"--field {field}: the message has no {where}") from None
        return _hide_arrays(value) if no_arr else value

    return show


def _hide_arrays(value: Any) -> Any:
    if isinstance(value, list):
        return f"<array, length: {len(value)}>"
    if isinstance(value, dict):
        return {key: _hide_arrays(item) for key, item in value.items()}
    return value


def to_csv(value: Any) -> str:
    """A message (or field) as one line of comma-separated values, in field order (ros2's --csv)."""
    flat: list[str] = []

    def walk(item: Any) -> None:
        if isinstance(item, dict):
            for child in item.values():
                walk(child)
        elif isinstance(item, list):
            for child in item:
                walk(child)
        elif isinstance(item, bool):
            flat.append("true" if item else "false")
        elif isinstance(item, str):
            flat.append('"' + item.replace('"', '""') + '"' if ("," in item or '"' in item or "\n" in item) else item)
        else:
            flat.append(str(item))

    walk(value)
    return ",".join(flat)
