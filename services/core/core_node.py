"""The core as a node: ``/skydeck_core`` reads and publishes topics on behalf of its clients.

A client of the core (the dashboard, ``skydeck topic echo|pub``, and the protocol adapters) does
not talk to nodes itself. Reading ``ws://CORE/drone/pose`` makes the core subscribe to the topic:
it links once to each publisher, however many clients read it, and hands every frame on as
received (taps). Publishing there makes the core a publisher of the topic, latched, served at
``/api/core/TOPIC`` like any node's topic, where subscribed nodes link. Both show in the graph
as what they are: the core's own subscriptions and publications.

The participant is registered in-process (it *is* the registry's process), and its topics are
served by one route that looks the topic up, so a topic nobody uses any more is forgotten.
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass

from services.core.registry import Registry
from services.core.settings import CoreSettings
from services.runtime.edge.outbox import Outbox
from services.runtime.endpoint import TopicEndpoint
from services.runtime.participant import Participant
from services.runtime.protocol import CoreFrameModel, PublishersFrame
from shared_models import Message

__all__ = ["CORE_NODE", "CORE_NODE_PATH", "CoreNode"]

CORE_NODE = "/skydeck_core"
CORE_NODE_PATH = "/api/core"
"""Where the core's own topics are served: ``ws://CORE/api/core/TOPIC``."""

_STATS_PERIOD_S = 1.0
_EARLY_S = 2.0
"""How long a client's new publication keeps its first messages for nodes that link late:
rosbridge for ROS 1 keeps them one second; a node's link here (the registry's push, then a
WebSocket handshake) can take longer on a loaded machine."""


@dataclass
class _Publication:
    """Clients publishing one topic through the core; ``latched`` of them latch it."""

    sockets: int = 0
    latched: int = 0
    expiry: asyncio.TimerHandle | None = None


class CoreNode:
    """The core's participant, its registration, and its clients' readings and publications."""

    def __init__(self, registry: Registry, settings: CoreSettings, core_url: str) -> None:
        self._registry = registry
        self._settings = settings
        self.participant = Participant(
            CORE_NODE, settings, on_endpoint=lambda _: None, on_service=lambda _: None, on_changed=self._changed
        )
        self.participant.url = core_url.rstrip("/") + CORE_NODE_PATH
        self._publications: dict[str, _Publication] = {}
        self._tasks: set[asyncio.Task[None]] = set()
        self._registered = False

    # -- life -------------------------------------------------------------------------------

    def start(self) -> None:
        """Register in the registry and report publishing rates (inside the core's loop)."""
        self.participant.start_links(self._spawn)
        self._registry.register(self.participant.describe(), self._inbox)
        self._registered = True
        self._spawn(self._report_stats())

    def stop(self) -> None:
        self.participant.stop_links()
        for task in self._tasks:
            task.cancel()
        for publication in self._publications.values():
            if publication.expiry is not None:
                publication.expiry.cancel()

    def _spawn(self, coroutine):  # type: ignore[no-untyped-def]
        task = asyncio.get_running_loop().create_task(coroutine)
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)
        return task

    def _inbox(self, frame: CoreFrameModel) -> None:
        if isinstance(frame, PublishersFrame):
            self.participant.set_publishers(frame.topic, frame.publishers)

    def _changed(self) -> None:
        if self._registered:
            self._registry.update(self.participant.describe(), self._inbox)

    async def _report_stats(self) -> None:
        while True:
            await asyncio.sleep(_STATS_PERIOD_S)
            self._registry.record_stats(CORE_NODE, self.participant.published_counts())

    # -- topics -------------------------------------------------------------------------------

    def endpoint(self, topic: str) -> TopicEndpoint | None:
        """The core's endpoint of ``topic``, if a client reads or publishes it now."""
        return self.participant.endpoints.get(topic)

    def start_reading(self, topic: str, outbox: Outbox) -> TopicEndpoint:
        """A client reads ``topic``: the core subscribes to it while anyone does."""
        endpoint = self.participant.endpoints.get(topic)
        if endpoint is None:
            endpoint = self.participant.add_endpoint(
                TopicEndpoint(topic, None, self._registry.topic_type(topic) or "")
            )
        first = not endpoint.taps
        endpoint.taps.add(outbox)
        if first:
            self._changed()  # the registry now tells the core this topic's publishers: links follow
        return endpoint

    def stop_reading(self, topic: str, outbox: Outbox) -> None:
        endpoint = self.participant.endpoints.get(topic)
        if endpoint is None:
            return
        endpoint.taps.discard(outbox)
        if not endpoint.taps:
            self.participant.set_publishers(topic, [])  # drops the links
            self._forget_if_unused(endpoint)
            self._changed()

    def start_publishing(self, topic: str, msg_type: type[Message], *, latched: bool = True) -> TopicEndpoint:
        """A client socket publishes ``topic``: the core publishes it, latched while any of its
        publishing clients latches it (every native socket does; a rosbridge client when it
        advertises with ``latch``)."""
        endpoint = self.participant.endpoint(msg_type, topic)
        publication = self._publications.setdefault(topic, _Publication())
        if publication.expiry is not None:
            publication.expiry.cancel()
            publication.expiry = None
        publication.sockets += 1
        publication.latched += latched
        if not endpoint.publishing:
            endpoint.hold_early(_EARLY_S)  # subscribed nodes link after this; what it sends first waits for them
        if not endpoint.publishing or endpoint.latched != (publication.latched > 0):
            endpoint.publishing = True
            endpoint.latched = publication.latched > 0
            self._changed()
        return endpoint

    def stop_publishing(self, topic: str, *, latched: bool = True) -> None:
        """A publishing socket closed; the topic stays advertised a little longer (linger), so
        ``topic pub --once`` reaches subscribers that link a moment later."""
        publication = self._publications.get(topic)
        if publication is None:
            return
        publication.sockets -= 1
        publication.latched -= latched
        endpoint = self.participant.endpoints.get(topic)
        if publication.sockets and endpoint is not None and endpoint.latched and not publication.latched:
            endpoint.latched = False
            self._changed()
        if publication.sockets == 0:
            publication.expiry = asyncio.get_running_loop().call_later(
                self._settings.gateway_linger_s, self._expire, topic
            )

    def _expire(self, topic: str) -> None:
        publication = self._publications.get(topic)
        if publication is None or publication.sockets:
            return
        del self._publications[topic]
        endpoint = self.participant.endpoints.get(topic)
        if endpoint is not None:
            endpoint.publishing = endpoint.latched = False
            self._forget_if_unused(endpoint)
            self._changed()

    def _forget_if_unused(self, endpoint: TopicEndpoint) -> None:
        if endpoint.publishing:
            return
        endpoint.forget_latest()  # stale once nobody reads it
        if not endpoint.taps and not endpoint.outboxes:
            del self.participant.endpoints[endpoint.name]
