"""A participant in the graph: what a node (or the core) publishes, subscribes to and serves.

It owns the topic endpoints and services, keeps one link per remote publisher of every topic it
subscribes to, and describes itself for the registry. It has no server and no session: a
:class:`~services.runtime.node.Node` serves it with its own uvicorn and registers it over a
session; the core serves its own participant inside its app and registers it in-process.
"""

from __future__ import annotations

import asyncio
import os
from collections.abc import Callable, Coroutine
from typing import Any

from services.runtime.edge.encoding import Encoding
from services.runtime.edge.links import PublisherLink
from services.runtime.endpoint import TopicEndpoint
from services.runtime.errors import NodeError
from services.runtime.protocol import Entity, ForeignNode, NodeDescription, PublisherAddress
from services.runtime.service import Service
from services.runtime.settings import ProcessSettings
from services.runtime.subscription import RawSubscription
from services.runtime.wire import MAX_QUEUE
from shared_models import Message, resolve_name
from shared_models.definitions.loader import definitions_of

__all__ = ["Participant"]

Spawn = Callable[[Coroutine[Any, Any, Any]], "asyncio.Task[Any]"]


class Participant:
    """Endpoints, services and links of one named participant (see the module docstring).

    ``on_endpoint`` and ``on_service`` are told about each new one (to serve it);
    ``on_changed`` whenever the description changes (to tell the registry).
    """

    def __init__(
        self,
        name: str,
        settings: ProcessSettings,
        *,
        on_endpoint: Callable[[TopicEndpoint], None],
        on_service: Callable[[Service], None],
        on_changed: Callable[[], None],
    ) -> None:
        self.name = name
        self.settings = settings
        self.pid = os.getpid()
        self.url = ""  # where others reach it; set when it serves
        self.endpoints: dict[str, TopicEndpoint] = {}
        self.services: dict[str, Service] = {}
        # (topic, publisher URL) -> the link and the task running it
        self.links: dict[tuple[str, str], tuple[PublisherLink, asyncio.Task[None]]] = {}
        # Other systems' participants it bridges to (a ROS 2 bridge's ROS 2 nodes), for the graph
        self.foreign: list[ForeignNode] = []
        # In a lockstep run (services.runtime.lockstep): links tell publishers who reads.
        self.in_lockstep = False
        self._spawn: Spawn | None = None
        self._on_endpoint = on_endpoint
        self._on_service = on_service
        self.changed = on_changed

    # -- entities -----------------------------------------------------------------------------

    def endpoint(self, msg_type: type[Message], topic: str) -> TopicEndpoint:
        """The endpoint of ``topic``, made on first use; one topic has one type here."""
        if not (isinstance(msg_type, type) and issubclass(msg_type, Message) and msg_type.__ros_type__):
            raise TypeError(f"expected a message type such as PointStamped, got {msg_type!r}")
        name = resolve_name(topic)
        endpoint = self.endpoints.get(name)
        if endpoint is None:
            if name in self.services:
                raise NodeError(f"{self.name} already has a service named {name}")
            return self.add_endpoint(TopicEndpoint(name, msg_type))
        if endpoint.msg_type is None:  # known by name only so far (the core's clients read it)
            endpoint.msg_type, endpoint.type_name = msg_type, msg_type.__ros_type__
        elif endpoint.msg_type is not msg_type:
            raise NodeError(
                f"{name} is already used with type {endpoint.type_name} in {self.name}, "
                f"not {msg_type.__ros_type__}"
            )
        return endpoint

    def add_endpoint(self, endpoint: TopicEndpoint) -> TopicEndpoint:
        """Adopt a new endpoint (the core makes some whose type it does not know)."""
        self.endpoints[endpoint.name] = endpoint
        self._on_endpoint(endpoint)
        return endpoint

    def add_service(self, service: Service) -> None:
        if service.name in self.services or service.name in self.endpoints:
            raise NodeError(f"{self.name} already has a topic or service named {service.name}")
        self.services[service.name] = service
        self._on_service(service)
        self.changed()

    # -- the registry -------------------------------------------------------------------------

    def describe(self) -> NodeDescription:
        """What this participant tells the core about itself."""
        publications, subscriptions = [], []
        for endpoint in self.endpoints.values():
            entity = Entity(name=endpoint.name, type=endpoint.type_name, latched=endpoint.latched)
            if endpoint.publishing:
                publications.append(entity)
            if endpoint.subscribed:
                subscriptions.append(entity)
        services = [Entity(name=s.name, type=s.srv_type.__ros_type__) for s in self.services.values()]
        types = [e.msg_type for e in self.endpoints.values() if e.msg_type is not None]
        return NodeDescription(
            name=self.name,
            url=self.url,
            pid=self.pid,
            publications=publications,
            subscriptions=subscriptions,
            services=services,
            foreign=self.foreign,
            interfaces=definitions_of([*types, *(s.srv_type for s in self.services.values())]),
        )

    def published_counts(self) -> dict[str, int]:
        """Messages published so far per topic (the core turns them into rates)."""
        return {e.name: e.published_count for e in self.endpoints.values() if e.publishing}

    # -- links to remote publishers -------------------------------------------------------------

    def start_links(self, spawn: Spawn) -> None:
        """Links may be made from now on, as tasks made by ``spawn``."""
        self._spawn = spawn

    def set_publishers(self, topic: str, publishers: list[PublisherAddress]) -> None:
        """The core's list of publishers of ``topic`` changed: connect and disconnect links."""
        endpoint = self.endpoints.get(topic)
        wanted: set[str] = set()
        if endpoint is not None and endpoint.subscribed and self._spawn is not None:
            wanted = {p.url.rstrip("/") for p in publishers} - {self.url}
        for key in [key for key in self.links if key[0] == topic and key[1] not in wanted]:
            self.links.pop(key)[1].cancel()
        if not wanted or endpoint is None or self._spawn is None:
            return
        depths = [s.queue_size for s in endpoint.subscriptions]
        depths += [tap.queue_size for tap in endpoint.taps if isinstance(tap, RawSubscription)]
        queue_size = min(max(depths, default=100), MAX_QUEUE)  # a publisher keeps at most MAX_QUEUE per reader
        # Nodes link in msgpack; a topic read here only raw (a recorder) links in JSON, so its
        # frames come as the publisher serialised them, never converted here.
        raw_only = bool(endpoint.taps) and not endpoint.subscriptions and all(
            isinstance(tap, RawSubscription) and tap.encoding is Encoding.JSON for tap in endpoint.taps
        )
        encoding = Encoding.JSON if raw_only else Encoding.MSGPACK
        names = {p.url.rstrip("/"): p.node for p in publishers}
        reader = self.name if self.in_lockstep else ""
        for url in wanted:
            if (topic, url) not in self.links:
                link = PublisherLink(
                    url,
                    topic,
                    endpoint.receive_link_frame,
                    publisher=names.get(url, ""),
                    reader=reader,
                    encoding=encoding,
                    queue_size=queue_size,
                    max_message_bytes=self.settings.max_message_bytes,
                    ping_interval_s=self.settings.ping_interval_s,
                    ping_timeout_s=self.settings.ping_timeout_s,
                    token=self.settings.token,
                )
                self.links[(topic, url)] = (link, self._spawn(link.run()))

    def lockstep_counts(self) -> tuple[list[tuple[str, str, int]], list[tuple[str, str, int]], bool]:
        """For a lockstep run: messages handed to each counted reader (topic, reader, count),
        messages each link delivered (topic, publisher, count), and whether a link is still
        connecting (a subscriber that is not yet linked would miss what is published now)."""
        sent = [
            (endpoint.name, reader, count)
            for endpoint in self.endpoints.values()
            for reader, count in endpoint.sent_to_readers()
        ]
        received = [(link.topic, link.publisher, link.received) for link, _ in self.links.values()]
        connecting = any(not link.connected.is_set() for link, _ in self.links.values())
        return sent, received, connecting

    def is_linked(self, topic: str) -> bool:
        """Whether ``topic`` reaches this participant from at least one publisher now (a link is
        connected, or it publishes it itself): what an action client waits for before sending a goal."""
        endpoint = self.endpoints.get(topic)
        if endpoint is not None and endpoint.publishing:
            return True  # its own publications reach its own subscriptions in-process
        return any(key[0] == topic and link.connected.is_set() for key, (link, _) in self.links.items())

    def stop_links(self) -> None:
        """Cancel every link (the participant stops)."""
        for _, task in self.links.values():
            task.cancel()
        self.links.clear()
        self._spawn = None
