"""Recordings in ROS 2's own encoding: MCAP's ``ros2`` profile, ``ros2msg`` schemas, CDR messages.

``skydeck bag record --encoding cdr`` writes what rosbag2 writes, so ``ros2 bag``, the
``rosbags`` library and ``mcap-ros2-support`` read it: each channel's schema is the ROS type's
``.msg`` definition with its dependencies (:func:`shared_models.ros2msg.definition_text`), each
message the CDR of the frame as received (:mod:`shared_models.cdr`). ``/clock`` is recorded as
ROS 2 types it, ``rosgraph_msgs/msg/Clock`` (the same bytes as Skydeck's Time).

Reading goes the other way for any CDR channel, whoever wrote it (a robot's ``ros2 bag
record``): its message is decoded with the definition in the file itself, so a newer ROS 2's
extra fields are read and left out, and becomes the JSON frame Skydeck's nodes take.
"""

from __future__ import annotations

import json
from collections.abc import Callable

from services.bag.errors import BagError
from services.bag.schemas import message_type
from shared_models import Message
from shared_models.cdr import CdrError, codec_for, codec_of, json_frame, keeper
from shared_models.errors import SkydeckError
from shared_models.ros2msg import (
    definition_text,
    parse_definition,
    ros2_type_name,
    skydeck_type_name,
)

__all__ = [
    "CDR_ENCODING",
    "CDR_PROFILE",
    "SCHEMA_ENCODING",
    "cdr_schema",
    "frame_decoder",
    "frame_encoder",
    "skydeck_type_name",
]

CDR_PROFILE = "ros2"
CDR_ENCODING = "cdr"
SCHEMA_ENCODING = "ros2msg"


def cdr_schema(topic: str, type_name: str) -> tuple[str, bytes]:
    """The schema name (the ROS 2 type) and ``ros2msg`` text of a Skydeck topic."""
    ros_name = ros2_type_name(topic, type_name)
    cls = message_type(type_name) if ros_name == type_name else message_type(ros_name)
    return ros_name, definition_text(cls).encode()


def frame_encoder(type_name: str) -> Callable[[str | bytes], bytes]:
    """What turns a JSON frame of ``type_name`` into its CDR."""
    codec = codec_of(message_type(type_name))

    def encode(frame: str | bytes) -> bytes:
        try:
            return codec.encode(json.loads(frame))
        except (CdrError, ValueError) as error:
            raise BagError(f"a {type_name} frame could not be written as CDR: {error}") from None

    return encode


def frame_decoder(topic: str, schema_name: str, schema: bytes) -> tuple[str, Callable[[bytes], str]]:
    """The Skydeck type of a CDR channel and what turns its messages into JSON frames; BagError
    naming the topic if the schema cannot be read or the type is not one Skydeck has."""
    try:
        specs = parse_definition(schema_name, schema.decode("utf-8"))
        name = next(iter(specs))
        codec = codec_for(name, specs)
    except (SkydeckError, UnicodeDecodeError) as error:
        raise BagError(f"{topic}: its ros2msg schema {schema_name} cannot be read: {error}") from None
    skydeck_name = skydeck_type_name(topic, name)
    cls: type[Message] = message_type(skydeck_name)
    keep = None
    if skydeck_name == name:
        keep = keeper(specs, name, cls)
    else:  # /clock's Clock is Time's bytes
        codec = codec_of(cls)

    def decode(data: bytes) -> str:
        try:
            value = codec.decode(data)
            return json_frame(keep(value) if keep is not None else value)
        except (CdrError, ValueError) as error:
            raise BagError(f"a message on {topic} could not be read: {error}") from None

    return skydeck_name, decode
