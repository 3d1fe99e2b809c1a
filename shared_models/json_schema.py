"""A message type's JSON schema, written from its ROS definition: the one writer for every reader.

Recordings (MCAP's ``jsonschema`` encoding) and the Foxglove endpoint's channels both describe
messages with it, named by the ROS type (``geometry_msgs/msg/PoseStamped``), which is what
Foxglove's and Lichtblick's panels are chosen by. What those readers take, and so what this
writes:

- every schema whole: nested types inline, no ``$ref`` (their schema readers follow none);
- every property a plain ``type`` (they know no ``anyOf``, ``null`` or missing types): ROS's
  integer types ``integer``, ``float32``/``float64`` ``number``, ``bool`` ``boolean``, strings
  ``string``; arrays with ``minItems``/``maxItems`` for fixed and bounded sizes;
- ``uint8``/``byte`` arrays, of any size (``uint8[16]`` too), as base64 text
  (``contentEncoding: base64``, which they decode to bytes), as a message's JSON writes them;
- a time (builtin_interfaces Time or Duration) as ROS 2's ``{sec, nanosec}`` and Foxglove's
  ``nsec``: Foxglove and Lichtblick read every time as ``{sec, nsec}`` (their 3D panel takes the
  nanoseconds from ``nsec`` alone), ROS 2 code from ``nanosec``. :func:`with_nsec` gives a
  frame's times both, as the Foxglove endpoint sends them; :func:`without_nsec` takes ``nsec``
  out again (or makes it ``nanosec``, for a time written Foxglove's way only).
"""

from __future__ import annotations

import functools
import json
import re
from typing import Any

from shared_models._message import Message
from shared_models.builtin_interfaces import Duration, Time
from shared_models.interfaces import field_types

__all__ = ["has_time", "json_schema", "json_schema_text", "with_nsec", "without_nsec"]

_INTEGERS = {"byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"}
_NUMBERS = {"float32", "float64"}
_BRACKETS = re.compile(r"\[(<=)?(\d*)\]$")
_TIMES = (Time, Duration)
# A time's nanoseconds as a key of an object (never inside a JSON string, where quotes are escaped).
_NANOSEC = re.compile(r'([{,]"nanosec":)(\d+)')


@functools.cache
def has_time(cls: type[Message]) -> bool:
    """Whether ``cls`` holds a Time or Duration anywhere (or is one)."""
    if issubclass(cls, _TIMES):
        return True
    return any(nested is not None and has_time(nested) for _, _, nested in field_types(cls))


@functools.cache
def json_schema(cls: type[Message]) -> dict[str, Any]:
    """The JSON schema of ``cls`` (see the module docstring), titled with its ROS type."""
    return _schema(cls)


@functools.cache
def json_schema_text(cls: type[Message]) -> str:
    """:func:`json_schema` as JSON text, declaring its draft (a Foxglove channel's ``schema``,
    a recording's schema data)."""
    return json.dumps({"$schema": "https://json-schema.org/draft/2020-12/schema", **_schema(cls)})


@functools.cache
def _schema(cls: type[Message]) -> dict[str, Any]:
    properties: dict[str, Any] = {}
    for name, text, nested in field_types(cls):
        bracket = _BRACKETS.search(text)
        base = text[: bracket.start()] if bracket else text
        if base in ("uint8", "byte") and bracket:  # bytes, as a message's JSON writes them, any size
            properties[name] = {"type": "string", "contentEncoding": "base64"}
            continue
        item = _schema(nested) if nested is not None else _primitive(base)
        if bracket is None:
            properties[name] = item
        else:
            array: dict[str, Any] = {"type": "array", "items": item}
            if bracket.group(2):
                array["maxItems"] = int(bracket.group(2))
                if not bracket.group(1):
                    array["minItems"] = int(bracket.group(2))
            properties[name] = array
    if issubclass(cls, _TIMES):
        properties["nsec"] = {"type": "integer", "minimum": 0, "description": "= nanosec (Foxglove's name)"}
    return {"type": "object", "title": cls.__ros_type__, "properties": properties}


def _primitive(ros_type: str) -> dict[str, Any]:
    if ros_type == "bool":
        return {"type": "boolean"}
    if ros_type in _INTEGERS:
        return {"type": "integer"}
    if ros_type in _NUMBERS:
        return {"type": "number"}
    return {"type": "string"}


def with_nsec(frame: str) -> str:
    """``frame`` (a message's JSON) with ``"nsec"`` beside every time's ``"nanosec"``."""
    return _NANOSEC.sub(r'\1\2,"nsec":\2', frame)


def without_nsec(text: str) -> str:
    """A message's JSON as ROS 2 writes it: a time given Foxglove's way (``{sec, nsec}``) gets
    ``nanosec``, and an ``nsec`` beside a ``nanosec`` goes; ValueError if it is not JSON."""
    if '"nsec"' not in text:
        return text
    return json.dumps(_ros2_times(json.loads(text)))


def _ros2_times(value: Any) -> Any:
    if isinstance(value, dict):
        value = {key: _ros2_times(item) for key, item in value.items()}
        if "nsec" in value and "sec" in value:
            nsec = value.pop("nsec")
            value.setdefault("nanosec", nsec)
        return value
    if isinstance(value, list):
        return [_ros2_times(item) for item in value]
    return value
