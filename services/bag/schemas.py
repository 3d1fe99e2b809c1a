"""How a recording describes its messages: MCAP's JSON encoding, with each ROS type's JSON schema.

A channel's schema is named by the ROS type (``geometry_msgs/msg/PoseStamped``), which is what
Foxglove and Lichtblick choose their panels by, and holds the type's JSON schema with every
``$ref`` written out in place (their schema readers do not follow references). ``uint8[]``
fields are the base64 strings a recording holds (``contentEncoding: base64``; a message may be
read from either form, but it is written in this one), so those tools decode them to bytes.
"""

from __future__ import annotations

import json
from functools import cache
from typing import Any

from services.bag.errors import BagError
from shared_models import Message, UnknownInterfaceError, get_interface

__all__ = [
    "MESSAGE_ENCODING",
    "PROFILE",
    "SCHEMA_ENCODING",
    "message_type",
    "schema_bytes",
]

PROFILE = ""
"""MCAP's ``ros1`` and ``ros2`` profiles require their binary encodings, so a JSON recording
declares none; readers pick panels by the schema names, which are the ROS type names."""
MESSAGE_ENCODING = "json"
SCHEMA_ENCODING = "jsonschema"


def message_type(type_name: str) -> type[Message]:
    """The message class of ``type_name``; BagError if no message type has that name."""
    try:
        found = get_interface(type_name)
    except UnknownInterfaceError as error:
        raise BagError(str(error).splitlines()[0]) from None
    if not issubclass(found, Message):
        raise BagError(f"{type_name} is a service type: only topics can be recorded")
    return found


@cache
def schema_bytes(type_name: str) -> bytes:
    """The self-contained JSON schema of a message type, as a recording stores it."""
    schema = message_type(type_name).model_json_schema()
    definitions = schema.pop("$defs", {})
    inlined = _inline(schema, definitions)
    inlined["title"] = type_name
    return json.dumps(inlined, separators=(",", ":")).encode()


def _inline(node: Any, definitions: dict[str, Any]) -> Any:
    if isinstance(node, dict):
        written = _as_written(node)
        if written is not None:
            return written
        reference = node.get("$ref")
        if isinstance(reference, str) and reference.startswith("#/$defs/"):
            target = definitions[reference.removeprefix("#/$defs/")]
            rest = {key: value for key, value in node.items() if key != "$ref"}
            return {**_inline(target, definitions), **_inline(rest, definitions)}
        return {key: _inline(value, definitions) for key, value in node.items()}
    if isinstance(node, list):
        return [_inline(item, definitions) for item in node]
    return node


def _as_written(node: dict[str, Any]) -> dict[str, Any] | None:
    """A bytes field (base64 text, or a list of integers, when read) as it is written: base64."""
    for option in node.get("anyOf", ()):
        if isinstance(option, dict) and option.get("contentEncoding") == "base64":
            rest = {key: value for key, value in node.items() if key != "anyOf"}
            return {**rest, "type": "string", "contentEncoding": "base64"}
    return None
