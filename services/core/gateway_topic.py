"""A topic as the core's clients see it: ``ws://CORE/TOPIC``, a TopicPort on the core node.

Reading gets every frame on the topic, from every publisher, as received; frames the socket
publishes go to every subscriber and every other reader, never back to itself (no echo). The
first valid frame fixes the socket's type: the topic's type in the registry, or ``?type=`` for a
topic nobody has declared yet.
"""

from __future__ import annotations

from services.core.core_node import CoreNode
from services.core.registry import Registry
from services.runtime.edge.encoding import decode
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.outbox import Frame
from services.runtime.edge.topic_socket import TopicConnection
from services.runtime.endpoint import TopicEndpoint
from services.runtime.wire import Close
from shared_models import Message, UnknownInterfaceError, get_interface

__all__ = ["GatewayTopic", "declared_type"]


def declared_type(type_name: str | None) -> type[Message] | None:
    """The message type named by ``?type=``, if one is given; FrameRejected(1008) if unknown."""
    if not type_name:
        return None
    try:
        declared = get_interface(type_name)
    except UnknownInterfaceError as error:
        raise FrameRejected(Close.POLICY, str(error).splitlines()[0]) from None
    if not issubclass(declared, Message):
        raise FrameRejected(Close.POLICY, f"{type_name} is a service type, not a message type")
    return declared


class GatewayTopic:
    """One client socket's view of one topic through the core node."""

    def __init__(self, core: CoreNode, registry: Registry, name: str, declared: type[Message] | None) -> None:
        self.name = name
        self._core = core
        self._registry = registry
        self._declared = declared
        self._type: type[Message] | None = None  # fixed by the first valid frame
        self._endpoint: TopicEndpoint | None = None  # the core's, once this socket publishes

    def open(self, connection: TopicConnection) -> Frame | None:
        if connection.outbox is None:
            return None
        endpoint = self._core.start_reading(self.name, connection.outbox)
        if endpoint.latest is not None and (endpoint.publishing or self._registry.is_latched(self.name)):
            return endpoint.latest.get(connection.encoding)
        return None

    def receive_frame(self, connection: TopicConnection, frame: Frame) -> None:
        msg_type = self._type or self._topic_type()
        msg = decode(frame, msg_type, msg_type.__ros_type__)  # before publishing: a bad first frame opens nothing
        endpoint = self._endpoint
        if endpoint is None:
            endpoint = self._endpoint = self._core.start_publishing(self.name, msg_type)
            self._type = msg_type
            connection.published = True
        endpoint.dispatch(msg, endpoint.frames_of(msg, frame), connection.outbox)

    def close(self, connection: TopicConnection) -> None:
        if connection.outbox is not None:
            self._core.stop_reading(self.name, connection.outbox)
        if connection.published:
            self._core.stop_publishing(self.name)

    def _topic_type(self) -> type[Message]:
        known = self._registry.topic_type(self.name)
        declared = self._declared
        if known is None:
            if declared is None:
                raise FrameRejected(
                    Close.POLICY, f"{self.name} has no type yet: add ?type=pkg/msg/Name to publish a new topic"
                )
            return declared
        if declared is not None and declared.__ros_type__ != known:
            raise FrameRejected(Close.POLICY, f"{self.name} is {known}, not {declared.__ros_type__}")
        try:
            msg_type = get_interface(known)
        except UnknownInterfaceError:
            raise FrameRejected(Close.POLICY, f"the core does not know {known}: publish to the node directly") from None
        return msg_type  # type: ignore[return-value]
