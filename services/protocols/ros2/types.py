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

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from typing import Any

from services.protocols.ros2.interface_build import NOT_BRIDGED
from services.protocols.ros2.rclpy_types import TypeNotAvailable, rclpy_class, rclpy_specs
from shared_models import Message, ServiceType, UnknownInterfaceError, get_interface
from shared_models.cdr import CdrCodec, codec_for, codec_of, keeper
from shared_models.errors import SkydeckError
from shared_models.ros2msg import ros2_type_name, skydeck_type_name

__all__ = ["MessageMapping", "NotBridged", "message_mapping", "ros2_type_name", "service_mappings", "skydeck_type_name"]


class NotBridged(SkydeckError):
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


def _skydeck_type(name: str, kind: type[Any], *, shown_as: str = "") -> Any:
    """Skydeck's class of ``name``, of ``kind`` (a message or a service); NotBridged if none."""
    try:
        found = get_interface(name)
    except UnknownInterfaceError:
        raise NotBridged(f"{shown_as or name} has no Skydeck counterpart (see `skydeck interface list`)") from None
    if not (isinstance(found, type) and issubclass(found, kind)):
        raise NotBridged(f"{name} is not a {'service' if kind is ServiceType else 'message'} type")
    return found


@cache
def message_mapping(skydeck_name: str, ros_name: str) -> MessageMapping:
    """The mapping of a message type (or a service's ``_Request``/``_Response``); raises
    :class:`NotBridged` naming the type and the reason."""
    package = skydeck_name.split("/", 1)[0]
    if package in NOT_BRIDGED:
        raise NotBridged(f"{skydeck_name} is Skydeck's own plumbing, not bridged to ROS 2", quiet=True)
    skydeck = _skydeck_type(skydeck_name, Message, shown_as=ros_name)
    try:
        ros_cls = rclpy_class(ros_name)
    except TypeNotAvailable as error:
        raise NotBridged(f"{skydeck_name} has no ROS 2 counterpart here: {error}") from None
    if ros_name != skydeck_name:  # /clock's Clock: the same bytes as Time (ros2_type_name)
        return MessageMapping(skydeck, ros_name, ros_cls, codec_of(skydeck), None)
    ros_specs = rclpy_specs(ros_cls)
    codec = codec_for(ros_name, ros_specs)
    return MessageMapping(skydeck, ros_name, ros_cls, codec, keeper(ros_specs, ros_name, skydeck))


def service_mappings(name: str) -> tuple[type[ServiceType], MessageMapping, MessageMapping]:
    """A service type's class and the mappings of its request and response."""
    service = _skydeck_type(name, ServiceType)
    return service, message_mapping(f"{name}_Request", f"{name}_Request"), message_mapping(
        f"{name}_Response", f"{name}_Response"
    )
