"""STAND-IN, TO BE REPLACED: node parameters for the behaviours until the SDK has its own.

The SDK's parameters (``Node.declare_parameter``, ``skydeck param``, ``--ros-args -p`` read by
``skydeck run``) are being written on the ``params`` branch. Until they reach ``main``, the
behaviours use this shim, with the same calls, so that replacing it is deleting this file,
dropping :class:`LocalParameters` from ``RobotBehaviour``'s bases and
:func:`take_parameter_overrides` from ``run_behaviour`` (``services/behaviours/robot.py``):

    self.declare_parameter("speed", 0.2)         # an override from --ros-args -p speed:=0.3 wins
    self.get_parameter("speed").value

Only ``--ros-args -p NAME:=VALUE`` is read (values as YAML, as ROS does); the parameters are
not visible to ``skydeck param`` until the SDK's replace these.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import yaml

from shared_models.errors import SkydeckError

__all__ = ["LocalParameters", "ParameterError", "ShimParameter", "take_parameter_overrides"]

_overrides: dict[str, Any] = {}


class ParameterError(SkydeckError, ValueError):
    """A parameter that is not declared, or an override that does not fit its parameter."""


@dataclass(frozen=True)
class ShimParameter:
    """A parameter's name and value, as rclpy's ``Parameter`` reads."""

    name: str
    value: Any


def take_parameter_overrides(argv: list[str]) -> list[str]:
    """Remove ``--ros-args -p NAME:=VALUE ...`` (up to ``--`` or the end) from ``argv``, keep the
    values for :meth:`LocalParameters.declare_parameter`, and return the rest."""
    rest: list[str] = []
    words = iter(argv)
    for word in words:
        if word != "--ros-args":
            rest.append(word)
            continue
        for ros_word in words:
            if ros_word == "--":
                break
            if ros_word not in ("-p", "--param"):
                raise ParameterError(f"unknown ROS argument {ros_word!r}: the behaviours read -p NAME:=VALUE")
            assignment = next(words, "")
            name, sep, text = assignment.partition(":=")
            if not sep or not name:
                raise ParameterError(f"-p needs NAME:=VALUE, got {assignment!r}")
            _overrides[name] = yaml.safe_load(text) if text.strip() else ""
    return rest


class LocalParameters:
    """``declare_parameter`` / ``get_parameter`` as rclpy's, with the command line's overrides."""

    def declare_parameter(self, name: str, value: Any) -> ShimParameter:
        """Declare ``name`` with its default ``value``; an override of the same type wins (an
        integer is taken for a float)."""
        declared: dict[str, ShimParameter] | None = getattr(self, "_shim_parameters", None)
        if declared is None:
            declared = {}
            self._shim_parameters = declared
        chosen = _overrides.get(name, value)
        if isinstance(value, float) and isinstance(chosen, int) and not isinstance(chosen, bool):
            chosen = float(chosen)
        if type(chosen) is not type(value):
            raise ParameterError(
                f"parameter {name!r} is a {type(value).__name__}, not {chosen!r} ({type(chosen).__name__})"
            )
        declared[name] = ShimParameter(name, chosen)
        return declared[name]

    def get_parameter(self, name: str) -> ShimParameter:
        declared = getattr(self, "_shim_parameters", {})
        if name not in declared:
            raise ParameterError(f"parameter {name!r} is not declared")
        return declared[name]  # type: ignore[no-any-return]
