"""One topic inside one participant (a node, or the core): the hub its frames pass through.

What the participant publishes is serialised once; the frame goes to every reader's outbox and
the message object to every local subscription, without copying. Frames from remote
publishers (links) are parsed only when a local subscription needs the message, and go on as
received to the taps (the core's gateway readers, who read everything on the topic).

As a :class:`~services.runtime.edge.TopicPort`, the endpoint is what a socket on the node's
own ``ws://NODE/TOPIC`` talks to.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

from pydantic import ValidationError

from services.runtime.edge.frames import is_complete, parse_frame
from services.runtime.edge.outbox import Outbox
from services.runtime.edge.topic_socket import TopicConnection
from shared_models import Message

if TYPE_CHECKING:
    from services.runtime.subscription import Subscription

__all__ = ["TopicEndpoint"]

logger = logging.getLogger("skydeck.runtime")


class TopicEndpoint:
    """One topic in one participant: its type, latest message, readers and subscriptions.

    ``msg_type`` is None only on the core, for a topic its clients read whose type it does not
    know: such frames are forwarded without being parsed.
    """

    def __init__(self, name: str, msg_type: type[Message] | None, type_name: str = "") -> None:
        self.name = name
        self.msg_type = msg_type
        self.type_name = msg_type.__ros_type__ if msg_type is not None else type_name
        self.latched = False
        self.publishing = False  # the participant publishes it (a publisher, or a client through it)
        self.latest_msg: Message | None = None
        self.latest_frame: str | None = None
        self.published_count = 0
        self.outboxes: set[Outbox] = set()  # readers of what this participant publishes
        self.taps: set[Outbox] = set()  # readers of everything on the topic (the core's clients)
        self.subscriptions: list[Subscription] = []

    @property
    def subscribed(self) -> bool:
        """Whether the participant wants this topic from its remote publishers."""
        return bool(self.subscriptions or self.taps)

    # -- messages ---------------------------------------------------------------------------

    def dispatch(self, msg: Message, frame: str, sender: Outbox | None = None) -> None:
        """Deliver a message this participant publishes: readers, taps, local subscriptions."""
        self.latest_msg = msg
        self.latest_frame = frame
        self.published_count += 1
        for outbox in self.outboxes:
            if outbox is not sender:
                outbox.push(frame)
        for tap in self.taps:
            if tap is not sender:
                tap.push(frame)
        for subscription in self.subscriptions:
            subscription.enqueue(msg)

    def receive(self, msg: Message, frame: str, sender: Outbox | None = None) -> None:
        """Deliver a message from elsewhere (a client of this node) to taps and subscriptions."""
        self.latest_msg = msg
        self.latest_frame = frame
        for tap in self.taps:
            if tap is not sender:
                tap.push(frame)
        for subscription in self.subscriptions:
            subscription.receive(msg)

    def dispatch_frame(self, frame: str) -> None:
        """Deliver a frame this participant publishes as it is (already serialised, trusted: a
        recording played back); parsed only if a local subscription needs the message."""
        self.latest_frame = frame
        self.published_count += 1
        for outbox in self.outboxes:
            outbox.push(frame)
        for tap in self.taps:
            tap.push(frame)
        msg = self._parse_for_subscriptions(frame)
        self.latest_msg = msg
        if msg is not None:
            for subscription in self.subscriptions:
                subscription.enqueue(msg)

    def receive_link_frame(self, frame: str) -> None:
        """A frame from a remote publisher, as received: parsed only if someone here needs it."""
        self.latest_frame = frame
        for tap in self.taps:
            tap.push(frame)
        msg = self._parse_for_subscriptions(frame)
        if msg is not None:
            self.latest_msg = msg
            for subscription in self.subscriptions:
                subscription.receive(msg)

    def _parse_for_subscriptions(self, frame: str) -> Message | None:
        """The frame as a message, if a local subscription needs one (None otherwise, or if it
        is not of the topic's type: then it is dropped for them, with a warning)."""
        if not self.subscriptions or self.msg_type is None:
            return None
        try:
            return self.msg_type.model_validate_json(frame)
        except ValidationError as error:
            logger.warning("dropped a message on %s that is not a %s: %s", self.name, self.type_name, error)
            return None

    # -- the node's own socket (TopicPort) --------------------------------------------------

    def open(self, connection: TopicConnection) -> str | None:
        """A socket reads what this participant publishes; a latched topic's latest goes first."""
        if connection.outbox is not None:
            self.outboxes.add(connection.outbox)
        return self.latest_frame if self.latched and self.publishing else None

    def receive_frame(self, connection: TopicConnection, text: str) -> None:
        """A client published ``text`` here: the node publishes it, or, if the node only
        subscribes to the topic, its subscriptions receive it."""
        if self.msg_type is None:  # never on a node's own endpoint; the core routes elsewhere
            raise TypeError(f"{self.name} has no message type here")
        msg = parse_frame(self.msg_type, self.type_name, text)
        frame = text if is_complete(msg) else msg.model_dump_json()
        connection.published = True
        if self.publishing:
            self.dispatch(msg, frame, connection.outbox)
        else:
            self.receive(msg, frame, connection.outbox)

    def close(self, connection: TopicConnection) -> None:
        if connection.outbox is not None:
            self.outboxes.discard(connection.outbox)
