"""The registry: which nodes are alive, what they publish, subscribe to and serve.

A node is in the registry while its session is open (the core's own participant is registered
in-process). Topics are indexed both ways, so a change costs what it touches: when a node's
publications change, only the subscribers of the topics that changed are told; when its
subscriptions change, only it is told about the publishers of its new topics. Subscribers hear
about new publishers as soon as they register, without polling.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from services.runtime.protocol import (
    CoreFrameModel,
    Entity,
    ForeignNode,
    NodeDescription,
    PublisherAddress,
    PublishersFrame,
)

__all__ = ["Inbox", "NodeRecord", "Registry"]

Inbox = Callable[[CoreFrameModel], None]
"""How a registered participant receives frames from the core (a session queues them)."""


@dataclass
class NodeRecord:
    """One live node and how to reach its session."""

    description: NodeDescription
    inbox: Inbox
    # Publishing rates from the node's cumulative counts: topic -> (count, monotonic time, rate).
    counters: dict[str, tuple[int, float, float | None]] = field(default_factory=dict)
    # What this node was last told about each topic it subscribes to.
    told: dict[str, tuple[tuple[str, str], ...]] = field(default_factory=dict)
    # The key the core forwards admitted calls to this node with (its session's; "" for none).
    key: str = field(default="", repr=False)
    # When its counts last grew (monotonic): the class page's last message age.
    last_published: float | None = None


def _names(entities: list[Entity]) -> set[str]:
    return {entity.name for entity in entities}


class Registry:
    """Live nodes by name, topic indexes derived from them, and change fan-out."""

    def __init__(self) -> None:
        self.nodes: dict[str, NodeRecord] = {}
        # topic -> names of the nodes publishing / subscribing to it (insertion-ordered)
        self._publishers: dict[str, dict[str, None]] = {}
        self._subscribers: dict[str, dict[str, None]] = {}
        self._services: dict[str, tuple[Entity, str]] = {}  # service -> it and the node hosting it
        self._watchers: list[Callable[[], None]] = []

    def watch(self, on_change: Callable[[], None]) -> Callable[[], None]:
        """Call ``on_change()`` after every change of the graph; returns what stops it."""
        self._watchers.append(on_change)
        return lambda: self._watchers.remove(on_change)

    def _notify(self) -> None:
        for on_change in list(self._watchers):
            on_change()

    # -- changes ------------------------------------------------------------------------------

    def register(self, description: NodeDescription, inbox: Inbox, *, key: str = "") -> NodeRecord | None:
        """Add or replace a node (``key``: what the core forwards calls to it with); returns the
        record it replaced (another session), if any."""
        previous = self.nodes.get(description.name)
        if previous is not None:
            self._unindex(previous.description)
        record = self.nodes[description.name] = NodeRecord(description, inbox, key=key)
        self._index(description)
        self._changed(previous.description if previous else None, record)
        self._notify()
        return previous if previous is not None and previous.inbox != inbox else None

    def update(self, description: NodeDescription, inbox: Inbox) -> None:
        """A registered node's entities changed."""
        record = self.nodes.get(description.name)
        if record is None or record.inbox != inbox:
            return
        previous = record.description
        self._unindex(previous)
        record.description = description
        self._index(description)
        self._changed(previous, record)
        self._notify()

    def unregister(self, name: str, inbox: Inbox) -> None:
        """A session ended: remove its node (unless a newer session took the name)."""
        record = self.nodes.get(name)
        if record is None or record.inbox != inbox:
            return
        del self.nodes[name]
        self._unindex(record.description)
        self._tell_subscribers(_names(record.description.publications))
        self._notify()

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
            if count and (last is None or count > last[0]):
                record.last_published = now
            record.counters[topic] = (count, now, rate)

    def _index(self, description: NodeDescription) -> None:
        for entity in description.publications:
            self._publishers.setdefault(entity.name, {})[description.name] = None
        for entity in description.subscriptions:
            self._subscribers.setdefault(entity.name, {})[description.name] = None
        for entity in description.services:
            self._services[entity.name] = (entity, description.name)

    def _unindex(self, description: NodeDescription) -> None:
        for index, entities in ((self._publishers, description.publications), (self._subscribers, description.subscriptions)):
            for entity in entities:
                names = index.get(entity.name)
                if names is not None:
                    names.pop(description.name, None)
                    if not names:
                        del index[entity.name]
        for entity in description.services:
            hosted = self._services.get(entity.name)
            if hosted is not None and hosted[1] == description.name:
                del self._services[entity.name]

    def _changed(self, before: NodeDescription | None, record: NodeRecord) -> None:
        after = record.description
        published_before = _names(before.publications) if before else set()
        published_after = _names(after.publications)
        moved = before is not None and before.url != after.url
        self._tell_subscribers((published_before ^ published_after) | (published_after if moved else set()))
        # The node itself: publishers of each topic it subscribes to (only what changed is sent).
        subscribed = _names(after.subscriptions)
        for topic in list(record.told):
            if topic not in subscribed:
                del record.told[topic]
        for topic in subscribed:
            self._tell(record, topic)

    def _tell_subscribers(self, topics: set[str]) -> None:
        for topic in topics:
            for name in list(self._subscribers.get(topic, ())):
                self._tell(self.nodes[name], topic)

    def _tell(self, record: NodeRecord, topic: str) -> None:
        addresses = self.publishers(topic)
        summary = tuple((a.node, a.url) for a in addresses)
        if record.told.get(topic) != summary:
            record.told[topic] = summary
            record.inbox(PublishersFrame(topic=topic, publishers=addresses))

    # -- queries ------------------------------------------------------------------------------

    def publishers(self, topic: str) -> list[PublisherAddress]:
        """Every live publisher of ``topic``, in registration order."""
        return [
            PublisherAddress(node=name, url=self.nodes[name].description.url)
            for name in self._publishers.get(topic, ())
        ]

    def subscribers(self, topic: str) -> list[str]:
        """The names of the nodes subscribed to ``topic``."""
        return list(self._subscribers.get(topic, ()))

    def _entities(self, topic: str, role: str) -> list[Entity]:
        index = self._publishers if role == "publications" else self._subscribers
        return [
            entity
            for name in index.get(topic, ())
            for entity in getattr(self.nodes[name].description, role)
            if entity.name == topic
        ]

    def topic_type(self, topic: str) -> str | None:
        """The type of ``topic`` as its publishers or subscribers declare it, if any does."""
        for role in ("publications", "subscriptions"):
            for entity in self._entities(topic, role):
                if entity.type:  # the core's own subscriptions may not know the type
                    return entity.type
        return None

    def is_latched(self, topic: str) -> bool:
        """Whether any publisher of ``topic`` latches it."""
        return any(entity.latched for entity in self._entities(topic, "publications"))

    def service(self, name: str) -> tuple[Entity, NodeRecord] | None:
        """The service called ``name`` and the node hosting it."""
        hosted = self._services.get(name)  # looked up on every call through the core: one dict get
        if hosted is None:
            return None
        entity, node = hosted
        return entity, self.nodes[node]

    def _foreign(self) -> list[tuple[str, ForeignNode]]:
        """Other systems' participants, each with the node that bridges to it, by name; a name a
        Skydeck node (or an earlier bridge) already has is listed once, as that one."""
        seen = set(self.nodes)
        found = []
        for name, record in sorted(self.nodes.items()):
            for foreign in record.description.foreign:
                if foreign.name not in seen:
                    seen.add(foreign.name)
                    found.append((name, foreign))
        return sorted(found, key=lambda item: item[1].name)

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
                **({"client": description.client} if description.client else {}),
            })
            for role, entities in (("publishers", description.publications), ("subscribers", description.subscriptions)):
                for entity in entities:
                    topic = _topic_entry(topics, entity)
                    topic["latched"] = topic["latched"] or (role == "publishers" and entity.latched)
                    topic[role].append(name)
            for topic_name, (_, _, rate) in record.counters.items():
                if topic_name in topics and rate is not None:
                    topics[topic_name]["rate_hz"] = round((topics[topic_name]["rate_hz"] or 0.0) + rate, 2)
            services.extend({"name": e.name, "type": e.type, "node": name} for e in description.services)
        for via, foreign in self._foreign():
            nodes.append(_foreign_node(foreign, via))
            for role, entities in (("publishers", foreign.publications), ("subscribers", foreign.subscriptions)):
                for entity in entities:
                    _topic_entry(topics, entity)[role].append(foreign.name)
        return {
            "nodes": sorted(nodes, key=lambda n: n["name"]),
            "topics": sorted(topics.values(), key=lambda t: t["name"]),
            "services": sorted(services, key=lambda s: s["name"]),
        }


def _topic_entry(topics: dict[str, dict[str, Any]], entity: Entity) -> dict[str, Any]:
    """The graph's entry of ``entity``'s topic, made on first use; its type from the first that says."""
    topic = topics.setdefault(
        entity.name,
        {"name": entity.name, "type": entity.type, "publishers": [], "subscribers": [], "rate_hz": None, "latched": False},
    )
    topic["type"] = topic["type"] or entity.type
    return topic


def _foreign_node(foreign: ForeignNode, via: str) -> dict[str, Any]:
    """A foreign participant as ``/api/graph`` lists it: no URL or pid of ours, its ``system``
    (``ros2``) and the node it is reached through (``via``)."""
    return {
        "name": foreign.name,
        "url": "",
        "pid": None,
        "publications": [e.name for e in foreign.publications],
        "subscriptions": [e.name for e in foreign.subscriptions],
        "services": [e.name for e in foreign.services],
        "system": foreign.system,
        "via": via,
    }
