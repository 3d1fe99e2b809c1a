"""ROS 2's own message classes (rclpy's): found by name, and read as a :class:`MessageSpec`.

The bridge encodes with the spec of the type the DDS side really has (the installed ROS 2
package's), which is Skydeck's own but for where ROS 2 moved on since Humble (Jazzy's
``sensor_msgs/Range.variance``): fields only ROS 2 has go out as zeros and are dropped on the way
in; fields only Skydeck has (``Header.seq``) stay home.
"""

from __future__ import annotations

import importlib
import re
from typing import Any

from shared_models.errors import SkydeckError
from shared_models.ros2msg import FieldSpec, MessageSpec

__all__ = ["TypeNotAvailable", "rclpy_class", "rclpy_specs"]

# rosidl's names of the primitives -> the .msg language's
_PRIMITIVES = {
    "boolean": "bool", "octet": "byte", "char": "char", "float": "float32", "double": "float64",
    "int8": "int8", "uint8": "uint8", "int16": "int16", "uint16": "uint16", "int32": "int32",
    "uint32": "uint32", "int64": "int64", "uint64": "uint64", "string": "string", "wstring": "wstring",
}
_SEQUENCE = re.compile(r"^sequence<(?P<item>[^,>]+)(?:,\s*(?P<bound>\d+))?>$")
_ARRAY = re.compile(r"^(?P<item>.+)\[(?P<size>\d+)\]$")


class TypeNotAvailable(SkydeckError, LookupError):
    """No ROS 2 package installed here defines the type (its message names why)."""


def rclpy_class(ros_type: str) -> Any:
    """ROS 2's class for ``pkg/msg/Name`` or ``pkg/srv/Name`` (``Name_Request`` is a service's
    request), imported from the installed packages; raises :class:`TypeNotAvailable`."""
    package, kind, short = ros_type.split("/")
    part = ""
    if kind == "srv" and short.endswith(("_Request", "_Response")):
        short, _, part = short.rpartition("_")
    try:
        module = importlib.import_module(f"{package}.{kind}")
    except ImportError:
        raise TypeNotAvailable(f"no ROS 2 package {package} is installed") from None
    cls = getattr(module, short, None)
    if cls is None:
        raise TypeNotAvailable(f"ROS 2's {package} has no {kind} {short}")
    return getattr(cls, part) if part else cls


def rclpy_specs(cls: Any) -> dict[str, MessageSpec]:
    """The spec of ROS 2's message class ``cls`` and of every type inside it, ``cls``'s first."""
    specs: dict[str, MessageSpec] = {}

    def add(message_cls: Any) -> str:
        name = _type_name(message_cls)
        if name not in specs:
            specs[name] = MessageSpec(name, ())  # claimed first, so a type seen twice is read once
            fields = []
            for field, text in message_cls.get_fields_and_field_types().items():
                fields.append(_field(field, text, add))
            specs[name] = MessageSpec(name, tuple(fields))
        return name

    add(cls)
    return specs


def _type_name(cls: Any) -> str:
    # rosidl's classes live in pkg.msg._module (or pkg.srv._module for a service's parts)
    package, kind = cls.__module__.split(".")[:2]
    return f"{package}/{kind}/{cls.__name__}"


def _field(name: str, text: str, add: Any) -> FieldSpec:
    array: int | None = None
    bounded = False
    if (match := _SEQUENCE.match(text)) is not None:
        text, array = match["item"].strip(), int(match["bound"]) if match["bound"] else -1
        bounded = match["bound"] is not None
    elif (match := _ARRAY.match(text)) is not None:
        text, array = match["item"], int(match["size"])
    text = re.sub(r"<=\d+$", "", text)  # a bounded string is a string in CDR
    if text in _PRIMITIVES:
        return FieldSpec(name, _PRIMITIVES[text], array, bounded)
    package, short = text.split("/")
    nested = getattr(importlib.import_module(f"{package}.msg"), short)
    return FieldSpec(name, add(nested), array, bounded)
