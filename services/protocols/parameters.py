"""Node parameters for the protocol clients, through each node's own ROS 2 parameter services.

Every node serves ``/NODE/list_parameters``, ``/NODE/get_parameters`` and
``/NODE/set_parameters`` (rcl_interfaces) and publishes changes on ``/parameter_events``.
Clients name a parameter with its node: ``/control.max_speed`` (foxglove_bridge's form, which
Skydeck sends) or ``/control:max_speed`` (rosapi's), both accepted everywhere. Values are plain
JSON (numbers, booleans, strings, arrays of one of them; bytes as base64 with a ``byte_array``
hint); a number sent for a float parameter stays a float, so ``3`` sets a double to 3.0.
"""

from __future__ import annotations

import asyncio
import base64
import binascii
from collections.abc import Awaitable, Callable, Iterable
from dataclasses import dataclass
from typing import Any

from pydantic import ValidationError

from services.core.registry import Registry
from services.core.service_calls import ServiceCallFailed, ServiceReply
from shared_models.errors import SkydeckError
from shared_models.rcl_interfaces import (
    GetParametersRequest,
    GetParametersResponse,
    ListParametersRequest,
    ListParametersResponse,
    Parameter,
    ParameterEvent,
    ParameterType,
    ParameterValue,
    SetParametersRequest,
    SetParametersResponse,
)

__all__ = [
    "ParameterError",
    "Parameters",
    "ParameterValueJson",
    "event_values",
    "from_value",
    "full_name",
    "split_name",
    "to_value",
]

Call = Callable[[str, bytes], Awaitable[ServiceReply]]
"""How parameters reach a node's services: the caller's own call path (its token)."""

_LIST, _GET, _SET = "/list_parameters", "/get_parameters", "/set_parameters"

# ParameterValue.type -> the field that holds the value.
_FIELDS = {
    ParameterType.PARAMETER_BOOL: "bool_value",
    ParameterType.PARAMETER_INTEGER: "integer_value",
    ParameterType.PARAMETER_DOUBLE: "double_value",
    ParameterType.PARAMETER_STRING: "string_value",
    ParameterType.PARAMETER_BYTE_ARRAY: "byte_array_value",
    ParameterType.PARAMETER_BOOL_ARRAY: "bool_array_value",
    ParameterType.PARAMETER_INTEGER_ARRAY: "integer_array_value",
    ParameterType.PARAMETER_DOUBLE_ARRAY: "double_array_value",
    ParameterType.PARAMETER_STRING_ARRAY: "string_array_value",
}
_ARRAYS = frozenset(kind for kind in _FIELDS if kind >= ParameterType.PARAMETER_BYTE_ARRAY)


class ParameterError(SkydeckError):
    """A parameter that cannot be named, read or written as asked (the message says why)."""

    http_status = 400


@dataclass(frozen=True)
class ParameterValueJson:
    """One parameter as clients see it: full name, JSON value, and Foxglove's type hint."""

    name: str
    value: Any  # None: not set
    type: str | None = None  # "float64", "float64_array", "byte_array" or None


def split_name(name: str) -> tuple[str, str]:
    """``/control.max_speed`` or ``/control:max_speed`` -> ``("/control", "max_speed")``."""
    node, separator, parameter = name.partition(":")
    if not separator:
        node, separator, parameter = name.partition(".")
    if not separator or not parameter or not node.startswith("/") or len(node) < 2:
        raise ParameterError(
            f"a parameter is named with its node: /NODE.PARAMETER or /NODE:PARAMETER, got {name!r}"
        )
    return node, parameter


def full_name(node: str, parameter: str) -> str:
    """The name Skydeck gives a parameter: ``/control.max_speed``."""
    return f"{node}.{parameter}"


def from_value(value: ParameterValue) -> tuple[Any, str | None]:
    """A ParameterValue as JSON and its type hint (floats are marked, so 3.0 stays a float)."""
    field = _FIELDS.get(value.type)
    if field is None:
        return None, None
    data = getattr(value, field)
    if value.type == ParameterType.PARAMETER_BYTE_ARRAY:
        return base64.b64encode(data).decode("ascii"), "byte_array"
    if value.type == ParameterType.PARAMETER_DOUBLE:
        return data, "float64"
    if value.type == ParameterType.PARAMETER_DOUBLE_ARRAY:
        return list(data), "float64_array"
    return (list(data) if isinstance(data, list) else data), None


def to_value(value: Any, hint: str | None = None, current: int = ParameterType.PARAMETER_NOT_SET) -> ParameterValue:
    """A JSON value as a ParameterValue; ``hint`` (Foxglove's) or the ``current`` type decides
    between integer and float. Raises ParameterError for a value no parameter can hold."""
    kind = _kind(value, hint, current)
    if kind == ParameterType.PARAMETER_NOT_SET:
        return ParameterValue()
    if kind == ParameterType.PARAMETER_BYTE_ARRAY:
        try:
            data = base64.b64decode(value, validate=True)
        except (binascii.Error, TypeError, ValueError):
            raise ParameterError("a byte_array parameter value must be base64 text") from None
        return ParameterValue(type=kind, byte_array_value=data)
    if kind == ParameterType.PARAMETER_DOUBLE:
        value = float(value)
    elif kind == ParameterType.PARAMETER_DOUBLE_ARRAY:
        value = [float(item) for item in value]
    try:
        return ParameterValue(type=kind, **{_FIELDS[kind]: value})
    except ValidationError as error:
        raise ParameterError(f"not a parameter value: {error.errors()[0]['msg']}") from None


def _kind(value: Any, hint: str | None, current: int) -> int:
    numbers = (ParameterType.PARAMETER_DOUBLE, ParameterType.PARAMETER_DOUBLE_ARRAY)
    if value is None:
        return ParameterType.PARAMETER_NOT_SET
    if hint == "byte_array":
        return ParameterType.PARAMETER_BYTE_ARRAY
    if isinstance(value, bool):
        return ParameterType.PARAMETER_BOOL
    if isinstance(value, int | float):
        if isinstance(value, float) or hint == "float64" or current == ParameterType.PARAMETER_DOUBLE:
            return ParameterType.PARAMETER_DOUBLE
        return ParameterType.PARAMETER_INTEGER
    if isinstance(value, str):
        return ParameterType.PARAMETER_STRING
    if isinstance(value, list):
        if not value:  # an empty list keeps the parameter's own array type
            return current if current in _ARRAYS else ParameterType.PARAMETER_STRING_ARRAY
        items = set(map(type, value))
        if items == {bool}:
            return ParameterType.PARAMETER_BOOL_ARRAY
        if items <= {int, float} and (float in items or hint == "float64_array" or current in numbers):
            return ParameterType.PARAMETER_DOUBLE_ARRAY
        if items == {int}:
            return ParameterType.PARAMETER_INTEGER_ARRAY
        if items == {str}:
            return ParameterType.PARAMETER_STRING_ARRAY
    raise ParameterError(f"a parameter value is a number, boolean, string or an array of one of them, not {value!r}")


def event_values(frame: str) -> list[ParameterValueJson]:
    """The parameters a ``/parameter_events`` frame sets (deleted ones as not set)."""
    event = ParameterEvent.model_validate_json(frame)
    values = [
        ParameterValueJson(full_name(event.node, p.name), *from_value(p.value))
        for p in (*event.new_parameters, *event.changed_parameters)
    ]
    values += [ParameterValueJson(full_name(event.node, p.name), None) for p in event.deleted_parameters]
    return values


class Parameters:
    """Reading and writing parameters of every node, through ``call`` (see the module docstring)."""

    def __init__(self, registry: Registry, call: Call) -> None:
        self._registry = registry
        self._call = call

    def nodes(self) -> list[str]:
        """The nodes that serve parameters (``/NODE/list_parameters``)."""
        return [
            service["node"]
            for service in self._registry.graph()["services"]
            if service["name"] == service["node"] + _LIST
        ]

    async def names(self) -> list[str]:
        """Every parameter of every node, as ``/node.parameter``."""
        lists = await asyncio.gather(*(self._list(node) for node in self.nodes()))
        return [full_name(node, name) for node, names in zip(self.nodes(), lists, strict=False) for name in names]

    async def get(self, names: Iterable[str] | None = None) -> list[ParameterValueJson]:
        """The values of ``names`` (every parameter when None); unknown ones are left out."""
        by_node: dict[str, list[str]] = {}
        if names is None:
            for name in await self.names():
                node, parameter = split_name(name)
                by_node.setdefault(node, []).append(parameter)
        else:
            for name in names:
                node, parameter = split_name(name)
                by_node.setdefault(node, []).append(parameter)
        answers = await asyncio.gather(*(self._get(node, params) for node, params in by_node.items()))
        found = []
        for (node, params), values in zip(by_node.items(), answers, strict=True):
            for parameter, value in zip(params, values, strict=False):
                if value.type != ParameterType.PARAMETER_NOT_SET:
                    found.append(ParameterValueJson(full_name(node, parameter), *from_value(value)))
        return found

    async def set(self, values: Iterable[ParameterValueJson]) -> list[tuple[str, bool, str]]:
        """Set each value on its node: ``(name, successful, reason)`` per value, in order."""
        by_node: dict[str, list[tuple[str, ParameterValueJson]]] = {}
        for item in values:
            node, parameter = split_name(item.name)
            by_node.setdefault(node, []).append((parameter, item))
        results: list[tuple[str, bool, str]] = []
        for node, items in by_node.items():
            current = await self._get(node, [parameter for parameter, _ in items])
            parameters = [
                Parameter(name=parameter, value=to_value(item.value, item.type, now.type))
                for (parameter, item), now in zip(items, current, strict=False)
            ]
            reply = await self._request(node + _SET, SetParametersRequest(parameters=parameters).model_dump_json())
            answer = SetParametersResponse.model_validate_json(reply.body)
            for (_, item), result in zip(items, answer.results, strict=False):
                results.append((item.name, result.successful, result.reason))
        return results

    async def _list(self, node: str) -> list[str]:
        try:
            reply = await self._request(node + _LIST, ListParametersRequest().model_dump_json())
        except ParameterError:
            return []  # a node that went away meanwhile has no parameters to show
        return ListParametersResponse.model_validate_json(reply.body).result.names

    async def _get(self, node: str, names: list[str]) -> list[ParameterValue]:
        reply = await self._request(node + _GET, GetParametersRequest(names=names).model_dump_json())
        return GetParametersResponse.model_validate_json(reply.body).values

    async def _request(self, service: str, body: str) -> ServiceReply:
        try:
            reply = await self._call(service, body.encode())
        except ServiceCallFailed as failed:
            raise ParameterError(str(failed)) from None
        if not reply.answered:
            raise ParameterError(f"{service}: {reply.detail()}")
        return reply

