"""A node's parameters, as ROS 2 has them: typed values declared with defaults, descriptors
(read-only, description, ranges), overrides from the command line, and on-set callbacks that may
refuse a change with a reason.

    speed = node.declare_parameter("speed", 0.2, ParameterDescriptor(description="m/s")).value
    node.add_on_set_parameters_callback(check)  # check(list[Parameter]) -> SetParametersResult

:class:`NodeParameters` is what a node holds (the :class:`~services.runtime.node.Node` methods
are rclpy's names for it); one value is a :class:`~services.runtime.parameter.Parameter`.
The exceptions keep rclpy's names::

    ParameterException (SkydeckError)
    ├── InvalidParameterException           a name that cannot be a parameter's
    ├── ParameterNotDeclaredException       a name never declared (undeclared ones not allowed)
    ├── ParameterAlreadyDeclaredException   declared twice
    ├── ParameterUninitializedException     read before it has a value (declared with a type only)
    ├── ParameterImmutableException         undeclaring a read-only parameter
    └── InvalidParameterValueException      declared with a value (or override) it refuses
        └── InvalidParameterTypeException   ... because the value is not of its type

A change refused at run time (wrong type, read-only, out of range, a callback said no) is not an
exception: it is a :class:`SetParametersResult` with ``successful=False`` and the reason.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from services.runtime.parameter import Parameter
from services.runtime.parameter import ParameterValueType as _Type
from shared_models.errors import SkydeckError
from shared_models.rcl_interfaces import (
    ListParametersResult,
    ParameterDescriptor,
    ParameterEvent,
    SetParametersResult,
)

__all__ = [
    "InvalidParameterException",
    "InvalidParameterTypeException",
    "InvalidParameterValueException",
    "NodeParameters",
    "ParameterAlreadyDeclaredException",
    "ParameterException",
    "ParameterImmutableException",
    "ParameterNotDeclaredException",
    "ParameterUninitializedException",
    "SetParametersCallback",
]

# Letters, digits and underscores in tokens separated by dots (ROS 2 also allows slashes:
# `qos_overrides./scan.publisher.depth`).
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*([./][A-Za-z0-9_]+)*")


# -- exceptions -------------------------------------------------------------------------------


class ParameterException(SkydeckError):
    """A parameter was used in a way the node cannot honour (the message says which and why)."""

    http_status = 400


class InvalidParameterException(ParameterException):
    """The name cannot be a parameter's."""


class ParameterNotDeclaredException(ParameterException):
    """The parameter was never declared, and the node does not allow undeclared parameters."""


class ParameterAlreadyDeclaredException(ParameterException):
    """The parameter is declared already."""


class ParameterUninitializedException(ParameterException):
    """The parameter was declared with a type but has no value yet."""


class ParameterImmutableException(ParameterException):
    """The parameter is read-only."""


class InvalidParameterValueException(ParameterException):
    """Declaring the parameter with this value (its default or its override) was refused."""


class InvalidParameterTypeException(InvalidParameterValueException):
    """The value given when declaring is not of the parameter's type."""


def _coerced(parameter: Parameter, declared: _Type) -> Parameter:
    """An integer given for a double (``param set /ai speed 2``) is taken as that double; an empty
    list as an empty list of the declared array type."""
    if declared is _Type.DOUBLE and parameter.type_ is _Type.INTEGER:
        return Parameter(parameter.name, _Type.DOUBLE, float(parameter.value))
    if declared is _Type.DOUBLE_ARRAY and parameter.type_ is _Type.INTEGER_ARRAY:
        return Parameter(parameter.name, _Type.DOUBLE_ARRAY, parameter.value)
    if declared.is_array and parameter.type_.is_array and not parameter.value:
        return Parameter(parameter.name, declared, [])
    return parameter


# -- a node's parameters ----------------------------------------------------------------------

SetParametersCallback = Callable[[list[Parameter]], SetParametersResult]


class NodeParameters:
    """The parameters of one node: declared values, descriptors, overrides and callbacks.

    ``overrides`` are the values given on the command line (``--ros-args -p``, params files):
    a parameter takes its override instead of its default when declared. ``on_event`` gets one
    ``ParameterEvent`` per accepted change (published on ``/parameter_events``).
    """

    def __init__(
        self,
        node_name: str,
        *,
        overrides: dict[str, Any] | None = None,
        allow_undeclared_parameters: bool = False,
        on_event: Callable[[ParameterEvent], None] = lambda _: None,
    ) -> None:
        self.node_name = node_name
        self.overrides = dict(overrides or {})
        self.allow_undeclared = allow_undeclared_parameters
        self._on_event = on_event
        self._values: dict[str, Parameter] = {}
        self._descriptors: dict[str, ParameterDescriptor] = {}
        # The node's add_/remove_..._parameters_callback edit these lists.
        self.on_set_callbacks: list[SetParametersCallback] = []
        """Asked in order before every change (``-> SetParametersResult``); the first refusal refuses it."""
        self.post_set_callbacks: list[Callable[[list[Parameter]], None]] = []
        """Told after every accepted change (to act on the new values)."""

    # -- declaring ----------------------------------------------------------------------------

    def declare(
        self,
        name: str,
        value: Any = None,
        descriptor: ParameterDescriptor | None = None,
        *,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare ``name`` with its default ``value`` (or a ``Parameter.Type`` for a typed
        parameter with no value yet, or None for a dynamically typed one); its override, if
        any, wins over the default. Raises when the value (or override) is refused."""
        self._check_name(name)
        if name in self._descriptors:
            raise ParameterAlreadyDeclaredException(f"parameter {name!r} of {self.node_name} is declared already")
        descriptor = (descriptor or ParameterDescriptor()).model_copy(update={"name": name})
        if isinstance(value, _Type):
            descriptor.type, value = int(value), None
        elif value is None:
            descriptor.dynamic_typing = True
        default = self._parameter(name, value, "its default")
        if default.type_ is not _Type.NOT_SET and not (default.type_.is_array and not default.value):
            descriptor.type = int(default.type_)
        # else: typed by the descriptor, or (an empty list) by the first non-empty list set later
        origin = "its default"
        if not ignore_override and name in self.overrides:
            origin = "its override: --ros-args -p or a params file"
            default = self._parameter(name, self.overrides[name], origin)
        if wrong_type := _type_refusal(descriptor, _coerced(default, _Type(descriptor.type)), declaring=True):
            raise InvalidParameterTypeException(f"{self.node_name}: {wrong_type} ({origin})")
        self._descriptors[name] = descriptor
        self._values[name] = Parameter(name)
        try:
            result = self._set_atomically([default], declaring=True)
        except BaseException:  # an on-set callback raised: nothing stays half-declared
            del self._descriptors[name], self._values[name]
            raise
        if not result.successful:
            del self._descriptors[name], self._values[name]
            raise InvalidParameterValueException(f"{self.node_name}: {result.reason} ({origin})")
        return self._values[name]

    def _parameter(self, name: str, value: Any, what: str) -> Parameter:
        try:
            return value if isinstance(value, Parameter) else Parameter(name, value=value)
        except (TypeError, ValueError) as error:
            raise InvalidParameterTypeException(f"{self.node_name}: parameter {name!r}: {error} ({what})") from None

    def undeclare(self, name: str) -> None:
        """Forget a declared parameter (read-only ones cannot be)."""
        descriptor = self._declared(name)
        if descriptor.read_only:
            raise ParameterImmutableException(f"parameter {name!r} of {self.node_name} is read-only")
        removed = self._values.pop(name)
        del self._descriptors[name]
        self._publish(deleted=[removed])

    # -- reading ------------------------------------------------------------------------------

    def has(self, name: str) -> bool:
        return name in self._descriptors

    @property
    def names(self) -> list[str]:
        return sorted(self._descriptors)

    def get(self, name: str) -> Parameter:
        """The parameter's current value; undeclared names are NOT_SET when the node allows them."""
        if name not in self._descriptors:
            if self.allow_undeclared:
                return Parameter(name)
            self._declared(name)  # raises
        parameter = self._values[name]
        if parameter.type_ is _Type.NOT_SET and not self._descriptors[name].dynamic_typing:
            raise ParameterUninitializedException(
                f"parameter {name!r} of {self.node_name} has no value yet: set it (e.g. --ros-args -p {name}:=...)"
            )
        return parameter

    def describe(self, name: str) -> ParameterDescriptor:
        return self._declared(name).model_copy(deep=True)

    def list_names(self, prefixes: Sequence[str] = (), depth: int = 0) -> ListParametersResult:
        """Names under ``prefixes`` (all when empty), at most ``depth`` dots down (0: any), and the
        prefixes (namespaces) those names are in, as ``list_parameters`` answers."""
        names: list[str] = []
        for name in sorted(self._descriptors):
            if prefixes:
                fits = any(
                    name.startswith(prefix + ".") and _within(name[len(prefix) + 1 :], depth) for prefix in prefixes
                )
            else:
                fits = _within(name, depth)
            if fits:
                names.append(name)
        namespaces = sorted({name.rsplit(".", 1)[0] for name in names if "." in name})
        return ListParametersResult(names=names, prefixes=namespaces)

    def _declared(self, name: str) -> ParameterDescriptor:
        descriptor = self._descriptors.get(name)
        if descriptor is None:
            raise ParameterNotDeclaredException(
                f"parameter {name!r} is not declared by {self.node_name}"
                + (f" (it has: {', '.join(self.names)})" if self._descriptors else "")
            )
        return descriptor

    def _check_name(self, name: str) -> None:
        if not isinstance(name, str) or not _NAME.fullmatch(name):
            raise InvalidParameterException(
                f"{name!r} is not a parameter name: letters, digits and '_' in tokens separated by '.'"
            )

    # -- setting ------------------------------------------------------------------------------

    def set(self, parameters: Iterable[Parameter]) -> list[SetParametersResult]:
        """Set each parameter on its own; one result per parameter, in order."""
        parameters = list(parameters)
        self._check_declared(parameters)
        return [self.set_atomically([parameter]) for parameter in parameters]

    def set_atomically(self, parameters: Iterable[Parameter]) -> SetParametersResult:
        """Set all of ``parameters``, or none of them when one is refused (the result says why).

        Raises ParameterNotDeclaredException for a name never declared when undeclared
        parameters are not allowed (rclpy does so too); an on-set callback's exception propagates.
        """
        parameters = list(parameters)
        self._check_declared(parameters)
        return self._set_atomically(parameters, declaring=False)

    def _check_declared(self, parameters: list[Parameter]) -> None:
        undeclared = [p.name for p in parameters if p.name not in self._descriptors]
        if undeclared and not self.allow_undeclared:
            raise ParameterNotDeclaredException(
                f"parameter(s) {', '.join(map(repr, undeclared))} not declared by {self.node_name}"
            )

    def _set_atomically(self, parameters: list[Parameter], *, declaring: bool) -> SetParametersResult:
        accepted: list[Parameter] = []
        for parameter in parameters:
            self._check_name(parameter.name)
            descriptor = self._descriptors.get(parameter.name)
            if descriptor is None:  # an undeclared one, allowed: typed by its value
                accepted.append(parameter)
                continue
            parameter = _coerced(parameter, _Type(descriptor.type))
            refusal = _refusal(descriptor, parameter, declaring=declaring)
            if refusal:
                return SetParametersResult(successful=False, reason=refusal)
            accepted.append(parameter)
        for callback in list(self.on_set_callbacks):
            result = callback(list(accepted))
            if not isinstance(result, SetParametersResult):
                raise TypeError(
                    f"on-set parameters callback {getattr(callback, '__qualname__', callback)!r} returned "
                    f"{type(result).__name__}, expected SetParametersResult"
                )
            if not result.successful:
                return result
        self._apply(accepted, declaring=declaring)
        return SetParametersResult(successful=True)

    def _apply(self, parameters: list[Parameter], *, declaring: bool) -> None:
        new: list[Parameter] = []
        changed: list[Parameter] = []
        deleted: list[Parameter] = []
        for parameter in parameters:
            name = parameter.name
            if parameter.type_ is _Type.NOT_SET and not declaring:
                deleted.append(self._values.pop(name))
                del self._descriptors[name]
                continue
            if name not in self._descriptors:
                self._descriptors[name] = ParameterDescriptor(name=name, dynamic_typing=True)
                new.append(parameter)
            else:
                (new if declaring else changed).append(parameter)
            descriptor = self._descriptors[name]
            if descriptor.type == _Type.NOT_SET and parameter.type_.is_array and parameter.value:
                descriptor.type = int(parameter.type_)  # declared with [], typed by its first list
            self._values[name] = parameter
        for callback in self.post_set_callbacks:
            callback(new + changed)
        self._publish(new=new, changed=changed, deleted=deleted)

    def _publish(
        self, *, new: Sequence[Parameter] = (), changed: Sequence[Parameter] = (), deleted: Sequence[Parameter] = ()
    ) -> None:
        self._on_event(
            ParameterEvent(
                node=self.node_name,
                new_parameters=[p.to_parameter_msg() for p in new],
                changed_parameters=[p.to_parameter_msg() for p in changed],
                deleted_parameters=[p.to_parameter_msg() for p in deleted],
            )
        )


def _within(relative_name: str, depth: int) -> bool:
    return depth == 0 or relative_name.count(".") < depth


def _refusal(descriptor: ParameterDescriptor, parameter: Parameter, *, declaring: bool) -> str:
    """Why ``parameter`` cannot be set under ``descriptor`` ('' when it can)."""
    name, value, type_ = parameter.name, parameter.value, parameter.type_
    if descriptor.read_only and not declaring:
        return f"parameter {name!r} is read-only"
    wrong_type = _type_refusal(descriptor, parameter, declaring=declaring)
    if wrong_type:
        return wrong_type
    if type_ is _Type.DOUBLE and descriptor.floating_point_range:
        bounds = descriptor.floating_point_range[0]
        return _range_refusal(name, value, bounds.from_value, bounds.to_value, bounds.step, tolerance=1e-9)
    if type_ is _Type.INTEGER and descriptor.integer_range:
        bounds_i = descriptor.integer_range[0]
        return _range_refusal(name, value, bounds_i.from_value, bounds_i.to_value, bounds_i.step, tolerance=0)
    return ""


def _type_refusal(descriptor: ParameterDescriptor, parameter: Parameter, *, declaring: bool) -> str:
    """Why ``parameter``'s type does not fit ``descriptor`` ('' when it does)."""
    name, value, type_ = parameter.name, parameter.value, parameter.type_
    declared = _Type(descriptor.type)
    if type_ is _Type.NOT_SET:
        if declaring or descriptor.dynamic_typing:
            return ""
        return f"parameter {name!r} is of type {declared.label} and cannot be unset"
    if descriptor.dynamic_typing:
        return ""
    if declared is _Type.NOT_SET:  # declared with an empty list: any list fits
        return "" if type_.is_array else f"parameter {name!r} is a list; got {type_.label} {value!r}"
    if type_ is not declared:
        return f"parameter {name!r} is of type {declared.label}; got {type_.label} {value!r}"
    return ""


def _range_refusal(name: str, value: float, low: float, high: float, step: float, *, tolerance: float) -> str:
    """ROS's range rule: within [low, high], and on a step from ``low`` (or exactly ``high``)."""
    slack = tolerance * max(1.0, abs(low), abs(high))
    if not low - slack <= value <= high + slack:
        return f"parameter {name!r} = {value!r} is outside its range [{low!r}, {high!r}]"
    if step and abs(value - high) > slack:
        off = (value - low) % step  # exact for integers
        if min(off, step - off) > slack:
            return f"parameter {name!r} = {value!r} is not on a step of {step!r} from {low!r}"
    return ""
