"""How the CLI prints messages (YAML, as rostopic echo does) and reads DATA (YAML or JSON)."""

from __future__ import annotations

from typing import Any

import yaml

from services.cli.errors import CliError

__all__ = ["parse_data", "to_yaml"]


def to_yaml(value: Any) -> str:
    """A message as block YAML, keys in field order."""
    return yaml.safe_dump(value, sort_keys=False, default_flow_style=False, allow_unicode=True).rstrip("\n")


def parse_data(text: str | None) -> dict[str, Any]:
    """DATA as given on the command line: YAML or JSON (``"{x: 1.0, y: 2.0}"``); empty is ``{}``."""
    if text is None or not text.strip():
        return {}
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        where = f" at column {mark.column + 1}" if mark is not None else ""
        raise CliError(f"DATA is not valid YAML or JSON{where}: {text!r}") from None
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise CliError(f"DATA must be a mapping of fields such as \"{{x: 1.0, y: 2.0}}\", got {text!r}")
    return value
