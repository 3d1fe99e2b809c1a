"""The hub of one topic inside a node: what the node publishes and receives on that topic.

Publishing serialises a message once; the frame then goes to every remote reader's outbox and
the message object to every local subscription, without copying.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from services.runtime.outbox import Outbox
from shared_models import Message

if TYPE_CHECKING:
    from services.runtime.subscription import Subscription

__all__ = ["TopicEndpoint"]


class TopicEndpoint:
    """One topic in one node: its type, latest message, remote readers and local subscriptions."""

    def __init__(self, name: str, msg_type: type[Message]) -> None:
        self.name = name
        self.msg_type = msg_type
        self.type_name = msg_type.__ros_type__
        self.latched = False
        self.publishing = False  # the node has a publisher (or a client published through it)
        self.latest_msg: Message | None = None
        self.latest_frame: str | None = None
        self.published_count = 0
        self.outboxes: set[Outbox] = set()
        self.subscriptions: list[Subscription] = []

    def dispatch(self, msg: Message, frame: str) -> None:
        """Deliver a message this node publishes: remote readers and local subscriptions."""
        self.latest_msg = msg
        self.latest_frame = frame
        self.published_count += 1
        for outbox in self.outboxes:
            outbox.push(frame)
        for subscription in self.subscriptions:
            subscription.enqueue(msg)

    def receive(self, msg: Message, frame: str) -> None:
        """Deliver a message received from a remote publisher to local subscriptions only."""
        self.latest_msg = msg
        self.latest_frame = frame
        for subscription in self.subscriptions:
            subscription.receive(msg)
