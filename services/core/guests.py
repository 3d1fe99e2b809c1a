"""Guests: clients of the core shown in the graph as the nodes they stand for.

A rosbridge or Foxglove connection, and rosapi, act through the core node (``/skydeck_core``
reads and publishes for them, and hosts their services), but ``skydeck node list`` and the graph
show each as a node of its own, named for what it is (``/rosbridge_client_3``,
``/foxglove_client_1``, ``/rosapi``), with the topics it reads and publishes and the services it
offers. Their URL is the core node's: that is where their topics are served and their services
answered (``POST /api/core/NAME``), so nodes and ``curl`` call a guest's service through the
gateway like any other.
"""

from __future__ import annotations

import itertools
import logging
import os
from collections import Counter
from collections.abc import Iterator
from typing import Protocol

from services.core.registry import Registry
from services.runtime.protocol import CoreFrameModel, Entity, NodeDescription
from shared_models import Message, ServiceType

__all__ = ["Guest", "Guests", "HostedService"]


class HostedService(Protocol):
    """A service the core answers in-process for a guest (rosapi's, a rosbridge client's), with
    the shape of the SDK's :class:`~services.runtime.service.Service` (which is one).

    ``handle`` may raise any SkydeckError: the caller gets its ``http_status`` and message.
    """

    name: str
    srv_type: type[ServiceType]

    async def handle(self, request: Message, logger: logging.Logger) -> Message: ...


class Guest:
    """One guest's entry in the graph: what it reads, publishes and serves."""

    def __init__(self, guests: Guests, name: str, client: str) -> None:
        self.name = name
        self.client = client
        self._guests = guests
        self._reads: Counter[str] = Counter()  # topic -> readings open (a client may read twice)
        self._publishes: dict[str, str] = {}  # topic -> type
        self.services: dict[str, HostedService] = {}
        self._types: dict[str, str] = {}  # topic -> type, where known

    # -- what it does (each call updates the graph) -----------------------------------------------

    def reads(self, topic: str, type_name: str = "") -> None:
        self._reads[topic] += 1
        if type_name:
            self._types[topic] = type_name
        if self._reads[topic] == 1:
            self._changed()

    def stops_reading(self, topic: str) -> None:
        if self._reads[topic] <= 1:
            self._reads.pop(topic, None)
            self._changed()
        else:
            self._reads[topic] -= 1

    def publishes(self, topic: str, type_name: str) -> None:
        if self._publishes.get(topic) != type_name:
            self._publishes[topic] = type_name
            self._changed()

    def stops_publishing(self, topic: str) -> None:
        if self._publishes.pop(topic, None) is not None:
            self._changed()

    def serves(self, service: HostedService) -> None:
        self.services[service.name] = service
        self._changed()

    def stops_serving(self, name: str) -> None:
        if self.services.pop(name, None) is not None:
            self._changed()

    # -- the registry -------------------------------------------------------------------------------

    def describe(self) -> NodeDescription:
        registry = self._guests.registry
        return NodeDescription(
            name=self.name,
            url=self._guests.url,
            pid=os.getpid(),
            client=self.client,
            publications=[Entity(name=topic, type=kind) for topic, kind in self._publishes.items()],
            subscriptions=[
                Entity(name=topic, type=self._types.get(topic) or registry.topic_type(topic) or "")
                for topic in self._reads
            ],
            services=[Entity(name=s.name, type=s.srv_type.__ros_type__) for s in self.services.values()],
        )

    def inbox(self, frame: CoreFrameModel) -> None:
        """What the registry tells the guest: nothing it acts on (the core node links for it)."""

    def _changed(self) -> None:
        if self._guests.registered(self):
            self._guests.registry.update(self.describe(), self.inbox)


class Guests:
    """The core's guests, registered in the registry under their own names."""

    def __init__(self, registry: Registry, url: str) -> None:
        self.registry = registry
        self.url = url  # the core node's: where guests' topics and services are served
        self._guests: dict[str, Guest] = {}
        self._numbers: dict[str, Iterator[int]] = {}

    def add(self, name: str, *, client: str = "", numbered: bool = False) -> Guest:
        """Register a guest called ``name`` (``/rosbridge_client`` + ``_N`` if ``numbered``)."""
        if numbered:
            counter = self._numbers.setdefault(name, itertools.count(1))
            name = f"{name}_{next(counter)}"
        guest = self._guests[name] = Guest(self, name, client)
        self.registry.register(guest.describe(), guest.inbox)
        return guest

    def remove(self, guest: Guest) -> None:
        if self._guests.get(guest.name) is guest:
            del self._guests[guest.name]
            self.registry.unregister(guest.name, guest.inbox)

    def registered(self, guest: Guest) -> bool:
        return self._guests.get(guest.name) is guest

    def service(self, name: str) -> HostedService | None:
        """The hosted service called ``name``, if a guest offers it."""
        for guest in self._guests.values():
            if (service := guest.services.get(name)) is not None:
                return service
        return None
