"""Topics through the gateway: the core as one more participant of every topic a client opens.

Reading ``ws://CORE/drone/pose``: the core links to every publisher of the topic once, however
many clients read it, and forwards each frame as received (no re-serialising) to every client's
outbox. Publishing on that socket: the core validates the frame, becomes a (latched) publisher
of the topic in the registry at ``/api/gateway``, and nodes subscribed to it link there.
"""

from __future__ import annotations

import asyncio
import logging
import os
from dataclasses import dataclass, field

from services.core.registry import Registry
from services.core.settings import CoreSettings
from services.runtime.links import PublisherLink
from services.runtime.outbox import Outbox
from services.runtime.protocol import Entity, NodeDescription
from shared_models import Message

__all__ = ["GATEWAY_NODE", "GATEWAY_PATH", "Relays"]

GATEWAY_NODE = "/skydeck_gateway"
GATEWAY_PATH = "/api/gateway"

logger = logging.getLogger("skydeck.core")


@dataclass
class _Relay:
    """One topic as seen by gateway readers."""

    outboxes: set[Outbox] = field(default_factory=set)
    links: dict[str, tuple[PublisherLink, asyncio.Task[None]]] = field(default_factory=dict)
    latest_frame: str | None = None

    def forward(self, frame: str) -> None:
        self.latest_frame = frame
        for outbox in self.outboxes:
            outbox.push(frame)


@dataclass
class _Publication:
    """One topic published through the gateway."""

    msg_type: type[Message]
    publishers: int = 0  # open sockets that have published on it
    outboxes: set[Outbox] = field(default_factory=set)  # nodes linked to /api/gateway/TOPIC
    latest_frame: str | None = None
    expiry: asyncio.TimerHandle | None = None


class Relays:
    """Every topic relayed or published by the gateway."""

    def __init__(self, registry: Registry, settings: CoreSettings, gateway_url: str) -> None:
        self._registry = registry
        self._settings = settings
        self.gateway_url = gateway_url.rstrip("/") + GATEWAY_PATH
        self._relays: dict[str, _Relay] = {}
        self.publications: dict[str, _Publication] = {}
        registry.topic_listeners.append(self._sync_links)

    # -- reading ------------------------------------------------------------------------------

    def attach(self, topic: str, outbox: Outbox) -> str | None:
        """Start relaying ``topic`` to ``outbox``; returns the latched frame to send first, if any."""
        relay = self._relays.get(topic)
        if relay is None:
            relay = self._relays[topic] = _Relay()
            self._sync_links(topic)
        relay.outboxes.add(outbox)
        publication = self.publications.get(topic)
        if publication is not None and publication.latest_frame is not None:
            return publication.latest_frame
        if relay.latest_frame is not None and self._registry.is_latched(topic):
            return relay.latest_frame
        return None

    def detach(self, topic: str, outbox: Outbox) -> None:
        """Stop relaying to ``outbox``; the last reader leaving closes the links."""
        relay = self._relays.get(topic)
        if relay is None:
            return
        relay.outboxes.discard(outbox)
        if not relay.outboxes:
            for _, task in relay.links.values():
                task.cancel()
            del self._relays[topic]

    def _sync_links(self, topic: str) -> None:
        relay = self._relays.get(topic)
        if relay is None:
            return
        wanted = {p.url.rstrip("/") for p in self._registry.publishers(topic) if p.node != GATEWAY_NODE}
        for url in list(relay.links):
            if url not in wanted:
                relay.links.pop(url)[1].cancel()
        for url in wanted - relay.links.keys():
            link = PublisherLink(
                url,
                topic,
                relay.forward,
                queue_size=100,
                max_message_bytes=self._settings.max_message_bytes,
                ping_interval_s=self._settings.ping_interval_s,
                ping_timeout_s=self._settings.ping_timeout_s,
                token=self._settings.token,
            )
            relay.links[url] = (link, asyncio.get_running_loop().create_task(link.run()))

    # -- publishing ---------------------------------------------------------------------------

    def publish(self, topic: str, msg: Message) -> None:
        """Publish a validated message from a gateway client to every subscriber of ``topic``."""
        publication = self.publications[topic]
        frame = msg.model_dump_json()
        publication.latest_frame = frame
        for outbox in publication.outboxes:
            outbox.push(frame)
        relay = self._relays.get(topic)
        if relay is not None:
            relay.forward(frame)

    def open_publication(self, topic: str, msg_type: type[Message]) -> None:
        """A socket starts publishing ``topic``: advertise the gateway as its publisher."""
        publication = self.publications.get(topic)
        if publication is None:
            publication = self.publications[topic] = _Publication(msg_type)
            self._advertise()
        if publication.expiry is not None:
            publication.expiry.cancel()
            publication.expiry = None
        publication.publishers += 1

    def close_publication(self, topic: str) -> None:
        """A publishing socket closed; the topic stays advertised a little longer (linger)."""
        publication = self.publications.get(topic)
        if publication is None:
            return
        publication.publishers -= 1
        if publication.publishers == 0:
            publication.expiry = asyncio.get_running_loop().call_later(
                self._settings.gateway_linger_s, self._expire, topic
            )

    def _expire(self, topic: str) -> None:
        publication = self.publications.get(topic)
        if publication is not None and publication.publishers == 0:
            del self.publications[topic]
            self._advertise()

    def _advertise(self) -> None:
        entities = [
            Entity(name=topic, type=p.msg_type.__ros_type__, latched=True) for topic, p in self.publications.items()
        ]
        if not entities:
            record = self._registry.nodes.get(GATEWAY_NODE)
            if record is not None:
                self._registry.unregister(GATEWAY_NODE, record.send)
            return
        description = NodeDescription(name=GATEWAY_NODE, url=self.gateway_url, pid=os.getpid(), publications=entities)
        if GATEWAY_NODE in self._registry.nodes:
            self._registry.update(description, _ignore)
        else:
            self._registry.register(description, _ignore)

    def close(self) -> None:
        """Stop every link (core shutdown)."""
        for relay in self._relays.values():
            for _, task in relay.links.values():
                task.cancel()
        self._relays.clear()


def _ignore(frame: str) -> None:
    """The gateway's own registry entry receives no session frames."""
