"""One topic inside one participant (a node, or the core): the hub its frames pass through.

What the participant publishes is serialised once per encoding its readers asked for (JSON text,
msgpack); the frame goes to every reader's outbox and the message object to every local
subscription, without copying. Frames from remote publishers (links; one may hold several
messages, :mod:`~services.runtime.edge.batch`) are parsed only when a local subscription needs
the message, and go on as received to the taps (the core's gateway readers, who read everything
on the topic).

As a :class:`~services.runtime.edge.TopicPort`, the endpoint is what a socket on the node's
own ``ws://NODE/TOPIC`` talks to.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from services.runtime.edge import batch
from services.runtime.edge.encoding import Frames, decode
from services.runtime.edge.frames import FrameRejected, is_complete
from services.runtime.edge.outbox import Frame, Outbox
from services.runtime.edge.topic_socket import TopicConnection
from shared_models import Message

if TYPE_CHECKING:
    from services.runtime.subscription import Subscription

__all__ = ["EARLY_FRAMES", "TopicEndpoint"]

logger = logging.getLogger("skydeck.runtime")

_monotonic = time.monotonic  # a global's lookup (and a test's clock), as in services.access.rates

EARLY_FRAMES = 20
"""At most this many of a new publication's first messages wait for its late readers (hold_early)."""


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
        self.latest: Frames | None = None
        self.published_count = 0
        self.outboxes: set[Outbox] = set()  # readers of what this participant publishes
        self.taps: set[Outbox] = set()  # readers of everything on the topic (the core's clients)
        self.subscriptions: list[Subscription] = []
        # Readers in a lockstep run (services.runtime.lockstep): their name, and the count of
        # messages published here before they came (every later one is handed to them).
        self._counted_readers: dict[Outbox, tuple[str, int]] = {}
        self._early: list[Frames] | None = None  # see hold_early
        self._early_until = 0.0

    @property
    def subscribed(self) -> bool:
        """Whether the participant wants this topic from its remote publishers."""
        return bool(self.subscriptions or self.taps)

    @property
    def latest_frame(self) -> str | None:
        """The latest message as JSON (``GET /TOPIC``), made when first asked for."""
        return self.latest.json if self.latest is not None else None

    def forget_latest(self) -> None:
        self.latest = None

    def hold_early(self, seconds: float) -> None:
        """Keep what is published in the next ``seconds`` (up to EARLY_FRAMES of it) for the
        readers that link within them.

        A subscriber links to a new publisher a moment after it advertises; a client that
        publishes at once (roslibpy's actionlib client sends its goal as soon as it hears the
        server's status) would reach no one. rosbridge for ROS 1 does the same for its clients'
        publishers (its PublisherConsistencyListener, one second)."""
        self._early = []
        self._early_until = _monotonic() + seconds

    def _still_early(self) -> bool:
        if self._early is not None and _monotonic() >= self._early_until:
            self._early = None
        return self._early is not None

    # -- messages ---------------------------------------------------------------------------

    def dispatch(self, msg: Message, frames: Frames | None = None, sender: Outbox | None = None) -> None:
        """Deliver a message this participant publishes: readers, taps, local subscriptions.

        Each encoding some reader wants is made once, for all of them (``frames``).
        """
        frames = Frames(msg) if frames is None else frames
        self.latest = frames
        self.published_count += 1
        if self._early is not None and self._still_early() and len(self._early) < EARLY_FRAMES:
            self._early.append(frames)
        for outbox in self.outboxes:
            if outbox is not sender:
                outbox.push(frames.get(outbox.encoding))
        for tap in self.taps:
            if tap is not sender:
                tap.push(frames.get(tap.encoding))
        for subscription in self.subscriptions:
            subscription.enqueue(msg)

    @property
    def read(self) -> bool:
        """Whether anyone reads what this participant publishes now (readers, taps, subscriptions)."""
        return bool(self.outboxes or self.taps or self.subscriptions)

    def dispatch_deferred(self, build: Callable[[], Message]) -> None:
        """Deliver the message ``build()`` makes if anyone reads the topic now; otherwise keep it
        unmade as the latest (``GET /TOPIC`` makes it), and count it as published."""
        if self.read:
            self.dispatch(build())
            return
        assert self.msg_type is not None, "only a publisher's own topic defers"
        self.latest = Frames.deferred(build, self.msg_type)
        self.published_count += 1

    def receive(self, msg: Message, frames: Frames, sender: Outbox | None = None) -> None:
        """Deliver a message from elsewhere (a client of this node) to taps and subscriptions."""
        self.latest = frames
        for tap in self.taps:
            if tap is not sender:
                tap.push(frames.get(tap.encoding))
        for subscription in self.subscriptions:
            subscription.receive(msg)

    def dispatch_frame(self, frame: str) -> None:
        """Deliver a JSON frame this participant publishes as it is (already serialised, trusted:
        a recording played back); other encodings are made from it if readers want them."""
        frames = Frames.received(frame, self.msg_type)
        self.latest = frames
        self.published_count += 1
        for outbox in self.outboxes:
            outbox.push(frames.get(outbox.encoding))
        for tap in self.taps:
            tap.push(frames.get(tap.encoding))
        msg = self._parsed(frames)
        if msg is not None:
            for subscription in self.subscriptions:
                subscription.enqueue(msg)

    def receive_link_frame(self, frame: Frame) -> int:
        """A frame from a remote publisher, as received: parsed only if someone here needs it;
        returns how many messages it held.

        A link's frame may be a batch: each of its messages is delivered as if it had come
        alone, in order."""
        if not batch.is_batch(frame):
            self._receive_from_link(Frames.received(frame, self.msg_type))
            return 1
        try:
            messages = batch.split(frame)
        except FrameRejected as error:
            logger.warning("dropped a frame on %s: %s", self.name, error.reason)
            return 0
        made = Frames.received if isinstance(frame, str) else Frames.unpacked
        for message in messages:
            self._receive_from_link(made(message, self.msg_type))
        return len(messages)

    def _receive_from_link(self, frames: Frames) -> None:
        self.latest = frames
        for tap in self.taps:
            tap.push(frames.get(tap.encoding))
        msg = self._parsed(frames)
        if msg is not None:
            for subscription in self.subscriptions:
                subscription.receive(msg)

    def _parsed(self, frames: Frames) -> Message | None:
        """The message for the local subscriptions, parsed once; None if nobody here needs it or
        it is not of the topic's type (then it is dropped, with a warning)."""
        if not self.subscriptions or self.msg_type is None:
            return None
        try:
            return frames.message()
        except FrameRejected as error:
            logger.warning("dropped a message on %s: %s", self.name, error.reason)
            return None

    def frames_of(self, msg: Message, frame: Frame) -> Frames:
        """The frames of ``msg``, parsed from ``frame``: the frame itself if it named every field,
        so it goes on as it came; otherwise made again, defaults filled in, for every reader."""
        if not is_complete(msg):
            return Frames(msg)
        if isinstance(frame, str):
            return Frames(msg, json_text=frame)
        return Frames(msg, packed=frame)

    # -- the node's own socket (TopicPort) --------------------------------------------------

    def open(self, connection: TopicConnection) -> Frame | None:
        """A socket reads what this participant publishes; a latched topic's latest goes first,
        an unlatched one's first messages if it was advertised a moment ago (hold_early)."""
        initial = None
        handed = 0
        if self.latched and self.publishing and self.latest is not None:
            initial = self.latest.get(connection.encoding)
            handed = 1
        elif self._still_early() and self._early and connection.outbox is not None:
            for frames in self._early:  # the outbox is drained once the socket serves
                connection.outbox.push(frames.get(connection.encoding))
            handed = len(self._early)
        if connection.outbox is not None:
            self.outboxes.add(connection.outbox)
            if connection.options.reader:
                self._counted_readers[connection.outbox] = (connection.options.reader, self.published_count - handed)
        return initial

    def sent_to_readers(self) -> list[tuple[str, int]]:
        """Messages handed to each reader in a lockstep run so far: (reader node, count)."""
        published = self.published_count
        return [(reader, published - already) for reader, already in self._counted_readers.values()]

    def receive_frame(self, connection: TopicConnection, frame: Frame) -> None:
        """A client published ``frame`` here: the node publishes it, or, if the node only
        subscribes to the topic, its subscriptions receive it."""
        if self.msg_type is None:  # never on a node's own endpoint; the core routes elsewhere
            raise TypeError(f"{self.name} has no message type here")
        msg = decode(frame, self.msg_type, self.type_name)
        frames = self.frames_of(msg, frame)
        connection.published = True
        if self.publishing:
            self.dispatch(msg, frames, connection.outbox)
        else:
            self.receive(msg, frames, connection.outbox)

    def close(self, connection: TopicConnection) -> None:
        if connection.outbox is not None:
            self.outboxes.discard(connection.outbox)
            self._counted_readers.pop(connection.outbox, None)
