"""Parsed definitions become message, service and action classes: the same kind of class as
the ones ``shared_models`` declares in Python (one type system).

A ``.msg`` file's fields become pydantic fields annotated with the same aliases a hand-written
type uses (``Int32``, ``Float64``, ``UInt8Array``...), its constants ``ClassVar`` attributes
named in ``__ros_constants__``, its header comment ``__ros_comment__``; so validation, JSON,
positional ROS 1 construction, ``interface show`` and the JSON schema are the shipped types' own.
Each class also names the definition it came from (``__ros_definition__``), which is how a
node tells the core about the types it uses (:mod:`shared_models.definitions.loader`).

Creating a class registers it under its ROS name (``Message.__init_subclass__``).
"""

from __future__ import annotations

import types
from collections.abc import Callable
from typing import Annotated, Any, ClassVar

from pydantic import ConfigDict, Field, Strict

from shared_models._message import (
    Base64Bytes,
    Bool,
    Byte,
    Declared,
    Float32,
    Float64,
    Int8,
    Int16,
    Int32,
    Int64,
    Message,
    RosPrimitive,
    ServiceType,
    String,
    UInt8,
    UInt16,
    UInt32,
    UInt64,
)
from shared_models.definitions.errors import DefinitionError
from shared_models.definitions.parser import Definition, FieldSpec, FieldType, MessageSpec

__all__ = ["Resolver", "message_class", "service_class"]

Resolver = Callable[[str, FieldSpec], type]
"""Finds the class registered as a field's type name (``geometry_msgs/msg/Point``), or raises
DefinitionError naming the field's line."""

_SCALARS: dict[str, Any] = {
    "bool": Bool,
    "byte": Byte,
    "char": Annotated[int, Strict(), RosPrimitive("char"), Field(ge=0, le=0xFF)],
    "int8": Int8,
    "uint8": UInt8,
    "int16": Int16,
    "uint16": UInt16,
    "int32": Int32,
    "uint32": UInt32,
    "int64": Int64,
    "uint64": UInt64,
    "float32": Float32,
    "float64": Float64,
    "string": String,
    "wstring": Annotated[str, Strict(), RosPrimitive("wstring")],
}
_ZEROS: dict[str, Any] = {"bool": False, "float32": 0.0, "float64": 0.0, "string": "", "wstring": ""}
_BYTES = ("uint8", "byte")  # their arrays are Python bytes, base64 in JSON, as the shipped types'
# A generated type's fields and constants are attributes of its class: none may hide a method
# every message has (copy, json, model_dump...).
_TAKEN = frozenset(name for name in dir(Message) if not name.startswith("__"))


def message_class(
    ros_type: str, spec: MessageSpec, resolve: Resolver, *, definition: Definition, class_name: str | None = None
) -> type[Message]:
    """The message class of ``spec``, registered as ``ros_type``."""
    name = class_name or ros_type.rsplit("/", 1)[-1]
    namespace: dict[str, Any] = {
        "__module__": f"{definition.package}.{definition.kind}",
        "__qualname__": name,
        "__doc__": _docstring(spec, ros_type),
        "__ros_type__": ros_type,
        "__ros_comment__": spec.comment,
        "__ros_constants__": tuple(c.name for c in spec.constants),
        "__ros_definition__": definition.ros_type,
        "model_config": ConfigDict(ser_json_bytes="base64", val_json_bytes="base64"),
    }
    annotations: dict[str, Any] = {}
    for constant in spec.constants:
        _check_free(constant.name, constant.line, definition)
        annotations[constant.name] = ClassVar[_SCALARS[constant.type]]  # type: ignore[valid-type]
        namespace[constant.name] = constant.value
    for field in spec.fields:
        _check_free(field.name, field.line, definition)
        annotations[field.name], namespace[field.name] = _field(field, resolve, definition)
    namespace["__annotations__"] = annotations
    try:
        return types.new_class(name, (Message,), exec_body=lambda ns: ns.update(namespace))
    except (TypeError, ValueError, NameError) as error:  # pydantic refusing a name or a default
        raise DefinitionError(definition.origin, None, f"cannot make {ros_type}: {error}") from None


def service_class(
    ros_type: str,
    request: MessageSpec,
    response: MessageSpec,
    resolve: Resolver,
    *,
    definition: Definition,
    joiner: str = "",
) -> tuple[type[Message], type[Message], type[ServiceType]]:
    """A service's request, response and service classes, registered as ``X_Request``,
    ``X_Response`` and ``X``; the parts' class names are ROS 1's (``XRequest``) or, with
    ``joiner="_"``, ROS 2's (an action's ``Fibonacci_SendGoal_Request``)."""
    short = ros_type.rsplit("/", 1)[-1]
    request_class = message_class(
        f"{ros_type}_Request", request, resolve, definition=definition, class_name=f"{short}{joiner}Request"
    )
    response_class = message_class(
        f"{ros_type}_Response", response, resolve, definition=definition, class_name=f"{short}{joiner}Response"
    )
    namespace = {
        "__module__": f"{definition.package}.{definition.kind}",
        "__qualname__": short,
        "__doc__": f"The service {ros_type}.",
        "__ros_type__": ros_type,
        "__ros_definition__": definition.ros_type,
        "Request": request_class,
        "Response": response_class,
    }
    service = types.new_class(short, (ServiceType,), exec_body=lambda ns: ns.update(namespace))
    return request_class, response_class, service


def _docstring(spec: MessageSpec, ros_type: str) -> str:
    lines = [line.lstrip("#").strip() for line in spec.comment.splitlines()]
    summary = next((line for line in lines if line), "")
    return summary or f"The message {ros_type}."


def _check_free(name: str, line: int, definition: Definition) -> None:
    if name in _TAKEN:
        raise DefinitionError(
            definition.origin, line, f"{name!r} cannot be a field or constant name in Skydeck: every message has a method of that name"
        )


def _field(field: FieldSpec, resolve: Resolver, definition: Definition) -> tuple[Any, Any]:
    """The annotation and the default (a value or a pydantic Field) of one field."""
    kind = field.type
    declared: tuple[Any, ...] = (Declared(),) if field.default is not None else ()
    least, most = _length(kind)
    annotation: Any
    if not kind.primitive:
        nested: Any = resolve(kind.base, field)
        if not issubclass(nested, Message):
            raise DefinitionError(definition.origin, field.line, f"{kind.base} is not a message type")
        if not kind.array:
            return nested, Field(default_factory=nested)
        size = kind.size or 0
        make = (lambda: [nested() for _ in range(size)]) if kind.fixed else list
        return list[nested], Field(default_factory=make, min_length=least, max_length=most)
    if kind.array and kind.base in _BYTES:
        annotation = Annotated[Base64Bytes, RosPrimitive(kind.base + kind.brackets()), *declared]
        if kind.fixed:
            default = bytes(field.default) if field.default is not None else bytes(kind.size or 0)
        else:
            default = bytes(field.default or ())
        return annotation, Field(default=default, min_length=least, max_length=most)
    item: Any = _scalar(kind)
    if kind.array:
        zero = _zero(kind.base)
        values = list(field.default) if field.default is not None else [zero] * (kind.size or 0) if kind.fixed else []
        annotation = Annotated[list[item], *declared] if declared else list[item]
        return annotation, Field(default_factory=lambda: list(values), min_length=least, max_length=most)
    annotation = Annotated[item, *declared] if declared else item
    return annotation, field.default if field.default is not None else _zero(kind.base)


def _scalar(kind: FieldType) -> Any:
    if kind.string_bound is None:
        return _SCALARS[kind.base]
    bound = kind.string_bound
    return Annotated[str, Strict(), RosPrimitive(kind.scalar_text()), Field(max_length=bound)]


def _zero(base: str) -> Any:
    return _ZEROS.get(base, 0)


def _length(kind: FieldType) -> tuple[int | None, int | None]:
    """The least and most items of an array field (None: no limit)."""
    if kind.size is None:
        return None, None
    if kind.bounded:
        return None, kind.size
    return kind.size, kind.size
