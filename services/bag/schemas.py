"""How a recording describes its messages: MCAP's JSON encoding, with each ROS type's JSON schema.

A channel's schema is named by the ROS type (``geometry_msgs/msg/PoseStamped``), which is what
Foxglove and Lichtblick choose their panels by, and is the type's JSON schema as
:mod:`shared_models.json_schema` writes it for every reader (the Foxglove endpoint's channels
too): whole, no ``$ref`` (their schema readers follow none), ``uint8[]`` fields as the base64
strings a recording holds (``contentEncoding: base64``; a message may be read from either form,
but it is written in this one), so those tools decode them to bytes.
"""

from __future__ import annotations

from services.bag.errors import BagError
from shared_models import Message, UnknownInterfaceError, get_interface
from shared_models.json_schema import json_schema_text

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


def schema_bytes(type_name: str) -> bytes:
    """The self-contained JSON schema of a message type, as a recording stores it (the one
    writer's: :func:`shared_models.json_schema.json_schema_text`)."""
    return json_schema_text(message_type(type_name)).encode()
