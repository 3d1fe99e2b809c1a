"""A topic as the core's clients see it: ``ws://CORE/TOPIC``, a TopicPort on the core node.

Reading gets every frame on the topic, from every publisher, as received; frames a client
publishes go to every subscriber and every other reader, never back to the client itself (no
echo). The first valid frame fixes the client's type: the topic's type in the registry, or the
declared one (``?type=``, rosbridge's ``advertise``) for a topic nobody has declared yet.

The native socket uses the three TopicPort calls; the protocol adapters, whose clients read and
publish one topic with separate lifetimes on one connection, use the four calls underneath
(``start_reading``, ``stop_reading``, ``publish``, ``stop_publishing``). Either way a frame is
validated, published and kept from echoing here and nowhere else.

Each view is fenced for its client (:class:`~services.access.fences.Pass`, ``visitor``):
reading is decided when it starts, publishing at the first frame (or advertise), so a message
costs only its subject's rate count (a student's: RateLimited, close 4002, once over). A view
the core makes for itself (``visitor=None``: Foxglove's clock, parameter events it filters) is
not fenced.
"""

from __future__ import annotations

from services.access import AccessRefused, Pass, RateLimited, Verb
from services.core.core_node import CoreNode
from services.core.registry import Registry
from services.runtime.edge.encoding import decode
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.outbox import Frame, Outbox
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
    """One client's view of one topic through the core node."""

    def __init__(
        self,
        core: CoreNode,
        registry: Registry,
        name: str,
        declared: type[Message] | None,
        *,
        visitor: Pass | None,
        latched: bool = True,
    ) -> None:
        self.name = name
        self._core = core
        self._registry = registry
        self._declared = declared
        self._latched = latched  # whether what this client publishes is latched (see CoreNode)
        self._type: type[Message] | None = None  # fixed by the first valid frame
        self._endpoint: TopicEndpoint | None = None  # the core's, once this client publishes
        self._visitor = None if visitor is None or visitor.unlimited else visitor  # None: nothing to check
        self._bucket = None if self._visitor is None else self._visitor.bucket  # a student's rate, per frame
        self._may_publish = self._visitor is None  # decided at the first publish

    @property
    def latched(self) -> bool:
        return self._latched

    # -- reading and publishing (what every client of the core does) ----------------------------

    def check(self, verb: Verb) -> None:
        """AccessRefused (401/403, 1008) unless this view's client may ``verb`` the topic."""
        if self._visitor is not None:
            self._visitor.check(verb, self.name)

    def start_reading(self, outbox: Outbox) -> Frame | None:
        """Frames on the topic go to ``outbox`` from now on; returns the latched frame, if any
        (in the outbox's encoding). AccessRefused if the client may not read it."""
        self.check(Verb.READ)
        endpoint = self._core.start_reading(self.name, outbox)
        if endpoint.latest is not None and (endpoint.latched or self._registry.is_latched(self.name)):
            return endpoint.latest.get(outbox.encoding)
        return None

    def stop_reading(self, outbox: Outbox) -> None:
        self._core.stop_reading(self.name, outbox)

    def advertise(self) -> None:
        """Publish the topic from now on, before the first frame (rosbridge's and Foxglove's
        advertise), so subscribers link to the core while the client gets ready. AccessRefused
        if the client may not publish it."""
        self._admit_publishing()
        if self._endpoint is None:
            msg_type = self.message_type()
            self._endpoint = self._core.start_publishing(self.name, msg_type, latched=self._latched)
            self._type = msg_type

    def publish(self, frame: Frame, sender: Outbox | None) -> bool:
        """Validate ``frame`` (JSON text, or msgpack bytes) and publish it through the core node, to everyone but ``sender``.

        Raises FrameRejected (1007 for a frame of the wrong type, 1008 for a topic with no
        type), AccessRefused (the client may not publish it), RateLimited (its subject sends
        too much). Returns True for this client's first frame (the core started publishing for it).
        """
        if not self._may_publish:
            self._admit_publishing()
        if self._bucket is not None:
            self._bucket.spend(len(frame))
        msg_type = self._type or self.message_type()
        msg = decode(frame, msg_type, msg_type.__ros_type__)  # before publishing: a bad first frame opens nothing
        endpoint = self._endpoint
        first = endpoint is None
        if endpoint is None:
            endpoint = self._endpoint = self._core.start_publishing(self.name, msg_type, latched=self._latched)
            self._type = msg_type
        endpoint.dispatch(msg, endpoint.frames_of(msg, frame), sender)
        return first

    def _admit_publishing(self) -> None:
        if not self._may_publish:
            self.check(Verb.PUBLISH)
            self._may_publish = True

    def stop_publishing(self) -> None:
        """This client publishes no more (the topic lingers, latched, as for a closed socket)."""
        if self._endpoint is not None:
            self._endpoint = None
            self._core.stop_publishing(self.name, latched=self._latched)

    def message_type(self) -> type[Message]:
        """The type a frame published here must have; FrameRejected(1008) when none is known."""
        if self._type is not None:
            return self._type
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

    # -- the native socket (TopicPort) ----------------------------------------------------------

    def open(self, connection: TopicConnection) -> Frame | None:
        if connection.outbox is None:  # publish-only: its fence is known now, so say it now
            self._admit_publishing()
            return None
        return self.start_reading(connection.outbox)

    def receive_frame(self, connection: TopicConnection, frame: Frame) -> None:
        try:
            first = self.publish(frame, connection.outbox)
        except (AccessRefused, RateLimited) as refused:
            raise FrameRejected(refused.close_code, str(refused)) from None
        if first:
            connection.published = True

    def close(self, connection: TopicConnection) -> None:
        if connection.outbox is not None:
            self.stop_reading(connection.outbox)
        if connection.published:
            self.stop_publishing()
