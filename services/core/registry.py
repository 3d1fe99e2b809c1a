"""The registry: which nodes are alive, what they publish, subscribe to and serve.

A node is in the registry while its session is open. After every change the registry works out,
for each session, the publishers of every topic it subscribes to, and sends only what changed:
subscribers hear about new publishers as soon as they register, without polling.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from services.runtime.protocol import Entity, NodeDescription, PublisherAddress, PublishersFrame

__all__ = ["NodeRecord", "Registry"]

# How a session receives frames from the core (the session handler queues them).
SendFrame = Callable[[str], None]


@dataclass
class NodeRecord:
    """One live node and its session."""

    description: NodeDescription
    send: SendFrame
    # Publishing rates from the node's cumulative counts: topic -> (count, monotonic time, rate).
    counters: dict[str, tuple[int, float, float | None]] = field(default_factory=dict)
    # What this session was last told about each subscribed topic.
    told: dict[str, tuple[tuple[str, str], ...]] = field(default_factory=dict)


class Registry:
    """Live nodes by name, the topic and service views derived from them, and change fan-out."""

    def __init__(self) -> None:
        self.nodes: dict[str, NodeRecord] = {}
        # Called with a topic name whenever its publishers may have changed (the gateway's relays).
        self.topic_listeners: list[Callable[[str], None]] = []

    # -- changes ------------------------------------------------------------------------------

    def register(self, description: NodeDescription, send: SendFrame) -> NodeRecord | None:
        """Add or replace a node; returns the record it replaced (another session), if any."""
        previous = self.nodes.get(description.name)
        self.nodes[description.name] = NodeRecord(description, send)
        self._changed(previous.description if previous else None, description)
        return previous if previous is not None and previous.send is not send else None

    def update(self, description: NodeDescription, send: SendFrame) -> None:
        """A registered node's entities changed."""
        record = self.nodes.get(description.name)
        if record is None or record.send is not send:
            return
        previous = record.description
        record.description = description
        self._changed(previous, description)

    def unregister(self, name: str, send: SendFrame) -> None:
        """A session ended: remove its node (unless a newer session took the name)."""
        record = self.nodes.get(name)
        if record is None or record.send is not send:
            return
        del self.nodes[name]
        self._changed(record.description, None)

    def record_stats(self, name: str, published: dict[str, int]) -> None:
        """Turn a node's cumulative publish counts into rates."""
        record = self.nodes.get(name)
        if record is None:
            return
        now = time.monotonic()
        for topic, count in published.items():
            last = record.counters.get(topic)
            rate = None
            if last is not None and now > last[1] and count >= last[0]:
                rate = (count - last[0]) / (now - last[1])
            record.counters[topic] = (count, now, rate)

    def _changed(self, before: NodeDescription | None, after: NodeDescription | None) -> None:
        topics: set[str] = set()
        for description in (before, after):
            if description is not None:
                topics.update(e.name for e in description.publications)
        for record in self.nodes.values():
            self._tell_publishers(record)
        for topic in topics:
            for listener in self.topic_listeners:
                listener(topic)

    def _tell_publishers(self, record: NodeRecord) -> None:
        for entity in record.description.subscriptions:
            addresses = self.publishers(entity.name)
            summary = tuple((a.node, a.url) for a in addresses)
            if record.told.get(entity.name) != summary:
                record.told[entity.name] = summary
                record.send(PublishersFrame(topic=entity.name, publishers=addresses).model_dump_json())

    # -- queries ------------------------------------------------------------------------------

    def publishers(self, topic: str) -> list[PublisherAddress]:
        """Every live publisher of ``topic``, in registration order."""
        return [
            PublisherAddress(node=name, url=record.description.url)
            for name, record in self.nodes.items()
            if any(e.name == topic for e in record.description.publications)
        ]

    def topic_type(self, topic: str) -> str | None:
        """The type of ``topic`` as its publishers or subscribers declare it, if any does."""
        for record in self.nodes.values():
            for entity in (*record.description.publications, *record.description.subscriptions):
                if entity.name == topic:
                    return entity.type
        return None

    def is_latched(self, topic: str) -> bool:
        """Whether any publisher of ``topic`` latches it."""
        return any(
            e.name == topic and e.latched for r in self.nodes.values() for e in r.description.publications
        )

    def service(self, name: str) -> tuple[Entity, NodeRecord] | None:
        """The service called ``name`` and the node hosting it."""
        for record in self.nodes.values():
            for entity in record.description.services:
                if entity.name == name:
                    return entity, record
        return None

    def graph(self) -> dict[str, Any]:
        """Nodes, topics (type, publishers, subscribers, rate) and services, as ``/api/graph``."""
        topics: dict[str, dict[str, Any]] = {}
        services: list[dict[str, str]] = []
        nodes: list[dict[str, Any]] = []
        for name, record in sorted(self.nodes.items()):
            description = record.description
            nodes.append({
                "name": name,
                "url": description.url,
                "pid": description.pid,
                "publications": [e.name for e in description.publications],
                "subscriptions": [e.name for e in description.subscriptions],
                "services": [e.name for e in description.services],
            })
            for role, entities in (("publishers", description.publications), ("subscribers", description.subscriptions)):
                for entity in entities:
                    topic = topics.setdefault(
                        entity.name,
                        {"name": entity.name, "type": entity.type, "publishers": [], "subscribers": [], "rate_hz": None},
                    )
                    topic[role].append(name)
            for topic_name, (_, _, rate) in record.counters.items():
                if topic_name in topics and rate is not None:
                    topics[topic_name]["rate_hz"] = round((topics[topic_name]["rate_hz"] or 0.0) + rate, 2)
            services.extend({"name": e.name, "type": e.type, "node": name} for e in description.services)
        return {
            "nodes": nodes,
            "topics": sorted(topics.values(), key=lambda t: t["name"]),
            "services": sorted(services, key=lambda s: s["name"]),
        }
