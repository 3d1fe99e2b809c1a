"""What Foxglove reads of a Skydeck topic: its JSON schema, and each frame as a payload.

Channels are ``encoding: json`` with ``schemaEncoding: jsonschema`` and the ROS type as the
schema name (``geometry_msgs/msg/PoseStamped``), so Foxglove's and Lichtblick's panels (3D,
plots, raw messages) treat them as the ROS types they are. Schemas are written out whole, nested
types inline (no ``$ref``), ``uint8[]`` as base64 text.

Foxglove reads a time as ``{sec, nsec}``; ROS 2's JSON says ``nanosec``. Every time in a payload
therefore carries both (``"nanosec": 5, "nsec": 5``), and the schemas declare both: ROS 2 code
reading the JSON and Foxglove's panels each find their field. The payload of a frame is made once
for every connection (:class:`Payloads`); only a type that holds a time pays for the rewrite.
"""

from __future__ import annotations

import functools
import json
import re
from typing import Any

from shared_models import Message, ServiceType
from shared_models.builtin_interfaces import Duration, Time
from shared_models.interfaces import field_types

__all__ = ["Payloads", "channel_schema", "has_time", "publishable_text", "service_schemas"]

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
def _schema(cls: type[Message]) -> dict[str, Any]:
    properties: dict[str, Any] = {}
    for name, text, nested in field_types(cls):
        bracket = _BRACKETS.search(text)
        base = text[: bracket.start()] if bracket else text
        if base in ("uint8", "byte") and bracket and not bracket.group(2):
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


@functools.cache
def channel_schema(cls: type[Message]) -> str:
    """The JSON schema of a message type, as a channel's ``schema`` text."""
    return json.dumps({"$schema": "https://json-schema.org/draft/2020-12/schema", **_schema(cls)})


def service_schemas(srv: type[ServiceType]) -> dict[str, Any]:
    """An ``advertiseServices`` entry's request and response descriptions (and the older
    ``requestSchema``/``responseSchema``, which some clients still read)."""
    request, response = channel_schema(srv.Request), channel_schema(srv.Response)
    return {
        "request": {
            "encoding": "json",
            "schemaName": srv.Request.__ros_type__,
            "schemaEncoding": "jsonschema",
            "schema": request,
        },
        "response": {
            "encoding": "json",
            "schemaName": srv.Response.__ros_type__,
            "schemaEncoding": "jsonschema",
            "schema": response,
        },
        "requestSchema": request,
        "responseSchema": response,
    }


class _Payload:
    __slots__ = ("frame", "payload", "times")

    def __init__(self, times: bool) -> None:
        self.times = times
        self.frame: str | None = None
        self.payload = b""


class Payloads:
    """Each topic's latest frame as a Foxglove payload, made once for every connection."""

    def __init__(self) -> None:
        self._topics: dict[tuple[str, type[Message]], _Payload] = {}

    def payload(self, topic: str, msg_type: type[Message], frame: str) -> bytes:
        slot = self._topics.get((topic, msg_type))
        if slot is None:
            slot = self._topics[(topic, msg_type)] = _Payload(has_time(msg_type))
        if frame is not slot.frame:  # every reader gets the same str object
            text = _NANOSEC.sub(r'\1\2,"nsec":\2', frame) if slot.times else frame
            slot.payload, slot.frame = text.encode(), frame
        return slot.payload


def publishable_text(payload: bytes) -> str:
    """A client's JSON payload as a Skydeck frame: a time it wrote as ``{sec, nsec}`` (Foxglove's
    way) gets ROS 2's ``nanosec``; raises ValueError for text that is not UTF-8 JSON."""
    text = payload.decode()
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
