"""Which ROS 2 type a Skydeck type is on the wire, and the two conversions between them.

A topic or service keeps its name and its type's name on both sides, with one exception: ROS 2's
``/clock`` is ``rosgraph_msgs/msg/Clock`` and Skydeck's is ``builtin_interfaces/msg/Time`` (the
seed's). A Clock is one Time, so their CDR is the same bytes: only the type name changes.

Messages cross as CDR, encoded and decoded by Skydeck's own codec (:mod:`shared_models.cdr`)
with the spec of the installed ROS 2 type, so rclpy never builds a Python message for a topic
(``publish(bytes)`` and ``raw=True`` subscriptions). Where that spec has fields Skydeck's type
lacks (Jazzy's ``Range.variance``), they go out as zeros and are dropped on the way in.
"""

from __future__ import annotations

import base64
import json
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from typing import Any

from services.protocols.ros2.interface_build import NOT_BRIDGED
from services.protocols.ros2.rclpy_types import TypeNotAvailable, rclpy_class, rclpy_specs
from shared_models import Message, ServiceType, UnknownInterfaceError, get_interface
from shared_models.cdr import CdrCodec, codec_for
from shared_models.ros2msg import MessageSpec, specs_of

__all__ = ["CLOCK_TOPIC", "MessageMapping", "NotBridged", "frame_text", "message_mapping", "ros_type_for", "skydeck_type_for"]

CLOCK_TOPIC = "/clock"
_TIME = "builtin_interfaces/msg/Time"
_CLOCK = "rosgraph_msgs/msg/Clock"


class NotBridged(Exception):
    """A type that cannot cross (one line: the type and why); ``quiet`` for Skydeck's own
    plumbing, which is never meant to cross and needs no warning."""

    def __init__(self, reason: str, *, quiet: bool = False) -> None:
        super().__init__(reason)
        self.quiet = quiet


@dataclass(frozen=True)
class MessageMapping:
    """One Skydeck message type and its ROS 2 counterpart."""

    skydeck: type[Message]
    ros_name: str
    ros_cls: Any
    codec: CdrCodec
    # Skydeck's fields where the ROS 2 spec has more (else None: nothing to drop)
    keep: Callable[[dict[str, Any]], dict[str, Any]] | None

    def to_ros(self, value: dict[str, Any]) -> bytes:
        """CDR of a message given as a dict (a JSON frame's, or ``model_dump()``'s)."""
        return self.codec.encode(value)

    def from_ros(self, data: bytes) -> dict[str, Any]:
        """The fields of a CDR message that Skydeck's type has."""
        value = self.codec.decode(data)
        return self.keep(value) if self.keep is not None else value


def ros_type_for(topic: str, skydeck_type: str) -> str:
    """The ROS 2 type of a Skydeck topic (the same name, but ``/clock``'s)."""
    return _CLOCK if topic == CLOCK_TOPIC and skydeck_type == _TIME else skydeck_type


def skydeck_type_for(topic: str, ros_type: str) -> str:
    """The Skydeck type of a ROS 2 topic (the same name, but ``/clock``'s)."""
    return _TIME if topic == CLOCK_TOPIC and ros_type == _CLOCK else ros_type


@cache
def message_mapping(skydeck_name: str, ros_name: str) -> MessageMapping:
    """The mapping of a message type (or a service's ``_Request``/``_Response``); raises
    :class:`NotBridged` naming the type and the reason."""
    package = skydeck_name.split("/", 1)[0]
    if package in NOT_BRIDGED:
        raise NotBridged(f"{skydeck_name} is Skydeck's own plumbing, not bridged to ROS 2", quiet=True)
    try:
        skydeck = get_interface(skydeck_name)
    except UnknownInterfaceError:
        raise NotBridged(f"{ros_name} has no Skydeck counterpart (see `skydeck interface list`)") from None
    if not (isinstance(skydeck, type) and issubclass(skydeck, Message)):
        raise NotBridged(f"{skydeck_name} is not a message type")
    try:
        ros_cls = rclpy_class(ros_name)
    except TypeNotAvailable as error:
        raise NotBridged(f"{skydeck_name} has no ROS 2 counterpart here: {error}") from None
    ros_specs = rclpy_specs(ros_cls)
    ours = specs_of(skydeck)
    if ros_name == _CLOCK and skydeck_name == _TIME:  # the same bytes (see the module docstring)
        return MessageMapping(skydeck, ros_name, ros_cls, codec_for(_TIME, ours), None)
    codec = codec_for(next(iter(ros_specs)), ros_specs)
    same = _shape(ros_specs, next(iter(ros_specs))) == _shape(ours, skydeck_name)
    keep = None if same else _keeper(ours, skydeck_name)
    return MessageMapping(skydeck, ros_name, ros_cls, codec, keep)


def service_mappings(name: str) -> tuple[type[ServiceType], MessageMapping, MessageMapping]:
    """A service type's class and the mappings of its request and response."""
    try:
        service = get_interface(name)
    except UnknownInterfaceError:
        raise NotBridged(f"{name} has no Skydeck counterpart (see `skydeck interface list --srv`)") from None
    if not (isinstance(service, type) and issubclass(service, ServiceType)):
        raise NotBridged(f"{name} is not a service type")
    return service, message_mapping(f"{name}_Request", f"{name}_Request"), message_mapping(
        f"{name}_Response", f"{name}_Response"
    )


def _shape(specs: dict[str, MessageSpec], name: str) -> Any:
    """A type's fields, names and kinds, with nested types written out (their names apart)."""
    spec = specs[name]
    return tuple(
        (f.name, f.type if f.is_primitive else _shape(specs, f.type), f.array, f.bounded) for f in spec.fields
    )


def _keeper(specs: dict[str, MessageSpec], name: str) -> Callable[[dict[str, Any]], dict[str, Any]]:
    def keep(value: dict[str, Any], type_name: str = name) -> dict[str, Any]:
        out = {}
        for item in specs[type_name].fields:
            if item.name not in value:
                continue
            field = value[item.name]
            if not item.is_primitive:
                field = [keep(v, item.type) for v in field] if item.array is not None else keep(field, item.type)
            out[item.name] = field
        return out

    return keep


def _json_default(value: Any) -> Any:
    if isinstance(value, bytes | bytearray):
        return base64.b64encode(value).decode("ascii")
    raise TypeError(f"cannot write {type(value).__name__} as JSON")


def frame_text(value: dict[str, Any]) -> str:
    """A Skydeck frame (JSON text) of a decoded message; raises ValueError for NaN or infinity,
    which Skydeck's messages refuse."""
    return json.dumps(value, default=_json_default, allow_nan=False, separators=(",", ":"))
