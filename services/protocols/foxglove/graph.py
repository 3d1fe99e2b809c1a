"""The graph as Foxglove clients see it: channels, services and the connection graph.

One view for every connection, rebuilt when the registry changes. Ids are stable: a topic keeps
its channel id for as long as it keeps its type (and a service its id), even across its absence,
as the protocol asks of a server that reuses ids.
"""

from __future__ import annotations

import itertools
from typing import Any

from services.core.registry import Registry
from shared_models import Message, ServiceType, UnknownInterfaceError, get_interface

__all__ = ["GraphView"]


class GraphView:
    """Channels (topics of a known message type) and services, with stable ids."""

    def __init__(self, registry: Registry) -> None:
        self._registry = registry
        self._channel_ids: dict[tuple[str, str], int] = {}
        self._service_ids: dict[tuple[str, str], int] = {}
        self._next_channel = itertools.count(1)
        self._next_service = itertools.count(1)
        self.channels: dict[int, tuple[str, type[Message]]] = {}
        self.services: dict[int, tuple[str, str, type[ServiceType]]] = {}
        self._graph: dict[str, Any] = {"topics": [], "services": [], "nodes": []}

    def update(self) -> None:
        """Read the registry again."""
        self._graph = graph = self._registry.graph()
        channels: dict[int, tuple[str, type[Message]]] = {}
        for topic in graph["topics"]:
            msg_type = _known(topic["type"], Message)
            if msg_type is None:
                continue  # a type the core does not know has no schema to offer
            key = (topic["name"], msg_type.__ros_type__)
            if key not in self._channel_ids:
                self._channel_ids[key] = next(self._next_channel)
            channels[self._channel_ids[key]] = (topic["name"], msg_type)
        services: dict[int, tuple[str, str, type[ServiceType]]] = {}
        for service in graph["services"]:
            srv_type = _known(service["type"], ServiceType)
            if srv_type is None:
                continue
            key = (service["name"], srv_type.__ros_type__)
            if key not in self._service_ids:
                self._service_ids[key] = next(self._next_service)
            services[self._service_ids[key]] = (service["name"], srv_type.__ros_type__, srv_type)
        self.channels, self.services = channels, services

    def graph_state(self) -> dict[str, Any]:
        """Who publishes, subscribes to and provides what, by name."""
        return {
            "published": {t["name"]: sorted(t["publishers"]) for t in self._graph["topics"] if t["publishers"]},
            "subscribed": {t["name"]: sorted(t["subscribers"]) for t in self._graph["topics"] if t["subscribers"]},
            "services": {s["name"]: [s["node"]] for s in self._graph["services"]},
        }

    def connection_graph(self, previous: dict[str, Any] | None) -> dict[str, Any] | None:
        """A ``connectionGraphUpdate`` from ``previous`` (None: everything) to now, or None if
        nothing changed."""
        now = self.graph_state()
        before = previous or {"published": {}, "subscribed": {}, "services": {}}
        if previous is not None and now == previous:
            return None
        topics_before = set(before["published"]) | set(before["subscribed"])
        topics_now = set(now["published"]) | set(now["subscribed"])

        def changed(kind: str) -> list[tuple[str, list[str]]]:
            names = sorted((set(before[kind]) | set(now[kind])) & (topics_now | set(now["services"])))
            return [(name, now[kind].get(name, [])) for name in names if before[kind].get(name) != now[kind].get(name)]

        return {
            "op": "connectionGraphUpdate",
            "publishedTopics": [{"name": name, "publisherIds": ids} for name, ids in changed("published")],
            "subscribedTopics": [{"name": name, "subscriberIds": ids} for name, ids in changed("subscribed")],
            "advertisedServices": [{"name": name, "providerIds": ids} for name, ids in changed("services")],
            "removedTopics": sorted(topics_before - topics_now),
            "removedServices": sorted(set(before["services"]) - set(now["services"])),
        }


def _known(type_name: str, kind: type) -> Any:
    if not type_name:
        return None
    try:
        found = get_interface(type_name)
    except UnknownInterfaceError:
        return None
    return found if isinstance(found, type) and issubclass(found, kind) else None
