"""A node's parameter methods, named and behaving as rclpy's ``Node``'s (the node mixes them in).

    class Follower(Node):
        def __init__(self):
            super().__init__("follower")
            self.declare_parameter("speed", 0.3, ParameterDescriptor(description="m/s"))
            self.add_on_set_parameters_callback(self.check)

        def check(self, parameters):
            for p in parameters:
                if p.name == "speed" and p.value > 1.0:
                    return SetParametersResult(successful=False, reason="speed is at most 1 m/s")
            return SetParametersResult(successful=True)

``self.get_parameter("speed").value`` reads it; ``skydeck param set /follower speed 0.5`` (or
:meth:`set_parameters`) changes it, asking ``check`` first.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from services.runtime.parameter import Parameter
from services.runtime.parameters import NodeParameters, SetParametersCallback
from shared_models.rcl_interfaces import ParameterDescriptor, SetParametersResult

__all__ = ["ParametersMixin"]


class ParametersMixin:
    """rclpy's parameter methods over the node's :class:`NodeParameters` (``self._parameters``)."""

    _parameters: NodeParameters

    # -- declaring ------------------------------------------------------------------------------

    def declare_parameter(
        self,
        name: str,
        value: Any = None,
        descriptor: ParameterDescriptor | None = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare ``name`` with its default ``value`` (its ``--ros-args -p`` override wins).

        ``value`` may be a ``Parameter.Type`` (typed, no value until set) or None (any type).
        A value or override that does not fit raises InvalidParameterValueException, naming it.
        """
        return self._parameters.declare(name, value, descriptor, ignore_override=ignore_override)

    def declare_parameters(
        self,
        namespace: str,
        parameters: Sequence[tuple[str] | tuple[str, Any] | tuple[str, Any, ParameterDescriptor]],
        ignore_override: bool = False,
    ) -> list[Parameter]:
        """Declare several: ``(name,)``, ``(name, value)`` or ``(name, value, descriptor)``, each
        named ``namespace.name`` (just ``name`` when ``namespace`` is empty)."""
        declared = []
        for entry in parameters:
            name, value, descriptor = (*entry, None, None)[:3]
            full_name = f"{namespace}.{name}" if namespace else name
            declared.append(self.declare_parameter(full_name, value, descriptor, ignore_override))
        return declared

    def undeclare_parameter(self, name: str) -> None:
        """Forget ``name`` (not a read-only one)."""
        self._parameters.undeclare(name)

    def has_parameter(self, name: str) -> bool:
        return self._parameters.has(name)

    # -- reading --------------------------------------------------------------------------------

    def get_parameter(self, name: str) -> Parameter:
        """The parameter ``name`` (``.value`` is its value); raises if it was never declared."""
        return self._parameters.get(name)

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        """The parameter ``name`` if declared, else ``alternative_value`` (NOT_SET if None)."""
        if self._parameters.has(name):
            return self._parameters.get(name)
        return alternative_value if alternative_value is not None else Parameter(name)

    def get_parameters(self, names: Sequence[str]) -> list[Parameter]:
        return [self._parameters.get(name) for name in names]

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """The parameters under ``prefix.``, by their names after it (all when ``prefix`` is '')."""
        start = f"{prefix}." if prefix else ""
        return {
            name[len(start) :]: self._parameters.get(name)
            for name in self._parameters.names
            if name.startswith(start)
        }

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        return self._parameters.describe(name)

    def describe_parameters(self, names: Sequence[str]) -> list[ParameterDescriptor]:
        return [self._parameters.describe(name) for name in names]

    # -- setting --------------------------------------------------------------------------------

    def set_parameters(self, parameter_list: Sequence[Parameter]) -> list[SetParametersResult]:
        """Set each parameter on its own; one result each (refusals say why)."""
        return self._parameters.set(parameter_list)

    def set_parameters_atomically(self, parameter_list: Sequence[Parameter]) -> SetParametersResult:
        """Set all of them, or none when one is refused."""
        return self._parameters.set_atomically(parameter_list)

    def add_on_set_parameters_callback(self, callback: SetParametersCallback) -> None:
        """``callback(list[Parameter]) -> SetParametersResult`` is asked before every change and
        may refuse it with a reason (``successful=False, reason=...``); the latest added is asked first."""
        self._parameters.on_set_callbacks.insert(0, callback)

    def remove_on_set_parameters_callback(self, callback: SetParametersCallback) -> None:
        self._parameters.on_set_callbacks.remove(callback)

    def add_post_set_parameters_callback(self, callback: Callable[[list[Parameter]], None]) -> None:
        """``callback(list[Parameter])`` after every accepted change (rclpy's post-set callback)."""
        self._parameters.post_set_callbacks.append(callback)

    def remove_post_set_parameters_callback(self, callback: Callable[[list[Parameter]], None]) -> None:
        self._parameters.post_set_callbacks.remove(callback)
