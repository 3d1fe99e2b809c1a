"""How a recording describes its messages: MCAP's JSON encoding, with each ROS type's JSON schema.

A channel's schema is named by the ROS type (``geometry_msgs/msg/PoseStamped``), which is what
Foxglove and Lichtblick choose their panels by, and holds the type's JSON schema with every
``$ref`` written out in place (their schema readers do not follow references). ``uint8[]``
fields carry ``contentEncoding: base64``, so those tools decode them back to bytes.
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
        reference = node.get("$ref")
        if isinstance(reference, str) and reference.startswith("#/$defs/"):
            target = definitions[reference.removeprefix("#/$defs/")]
            rest = {key: value for key, value in node.items() if key != "$ref"}
            return {**_inline(target, definitions), **_inline(rest, definitions)}
        return {key: _inline(value, definitions) for key, value in node.items()}
    if isinstance(node, list):
        return [_inline(item, definitions) for item in node]
    return node
