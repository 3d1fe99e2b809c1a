"""A guest's node-like hands in the core: publishers, subscriptions, services and a clock.

What an :class:`~services.runtime.actions.server.ActionServer` (or the TF republisher) needs of
a node, for a guest of the core: an action a rosbridge client serves, ``/tf2_web_republisher``.
Everything goes through the core node as for any client of the core: a publisher is the core
publishing the topic (``CoreNode.start_publishing``), a subscription a tap on its reading
(``CoreNode.start_reading``), a service one the core answers in-process; the guest shows each in
the graph. ``close`` ends them all.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

import services.protocols.rosbridge.clock as clock
from services.core.access import CoreAccess
from services.core.guests import Guest
from services.runtime.clock import ClockTime
from services.runtime.service import Service
from services.runtime.subscription import RawSubscription
from shared_models import Message, ServiceType, resolve_name

__all__ = ["CoreHost", "CorePublisher", "CoreTap"]

logger = logging.getLogger("skydeck.rosbridge")


class CorePublisher:
    """The core publishing one topic for a guest: ``publish(msg)`` reaches every subscriber."""

    def __init__(self, host: CoreHost, msg_type: type[Message], topic: str, *, latched: bool) -> None:
        self.topic = topic
        self._host = host
        self._latched = latched
        self._endpoint = host.access.core.start_publishing(topic, msg_type, latched=latched)
        host.guest.publishes(topic, msg_type.__ros_type__)

    def publish(self, msg: Message) -> None:
        self._endpoint.dispatch(msg)

    @property
    def read(self) -> bool:
        """Whether anyone reads the topic now (a node linked to the core, a client of the core)."""
        return self._endpoint.read

    def close(self) -> None:
        self._host.access.core.stop_publishing(self.topic, latched=self._latched)
        self._host.guest.stops_publishing(self.topic)


class CoreTap:
    """A guest reading one topic: ``callback(msg)`` for each message, on the event loop."""

    def __init__(self, host: CoreHost, msg_type: type[Message], topic: str, callback: Callable[[Any], None], depth: int) -> None:
        self.topic = topic
        self._host = host
        self._tap = RawSubscription(topic, msg_type, lambda frame: callback(msg_type.model_validate_json(frame)), depth)
        host.access.core.start_reading(topic, self._tap)
        host.guest.reads(topic, msg_type.__ros_type__)

    def close(self) -> None:
        self._host.access.core.stop_reading(self.topic, self._tap)
        self._host.guest.stops_reading(self.topic)


class _CoreClock:
    """The core's ROS time (:mod:`.clock`), as a node's clock: ``now().to_msg()``."""

    def __init__(self, access: CoreAccess) -> None:
        self._access = access

    def now(self) -> ClockTime:
        return ClockTime(clock.now(self._access).to_nsec())


class CoreHost:
    """A guest's publishers, taps and services in the core (see the module docstring)."""

    def __init__(self, access: CoreAccess, guest: Guest) -> None:
        self.access = access
        self.guest = guest
        self._clock = _CoreClock(access)
        self._publishers: list[CorePublisher] = []
        self._taps: list[CoreTap] = []
        self._services: list[str] = []

    def resolve_topic_name(self, topic: str) -> str:
        return resolve_name(topic)

    def get_clock(self) -> _CoreClock:
        return self._clock

    def create_publisher(
        self, msg_type: type[Message], topic: str, qos_profile: int = 10, *, latched: bool = False
    ) -> CorePublisher:
        publisher = CorePublisher(self, msg_type, resolve_name(topic), latched=latched)
        self._publishers.append(publisher)
        return publisher

    def destroy_publisher(self, publisher: CorePublisher) -> None:
        if publisher in self._publishers:
            self._publishers.remove(publisher)
            publisher.close()

    def create_subscription(
        self, msg_type: type[Message], topic: str, callback: Callable[[Any], None], qos_profile: int = 10
    ) -> CoreTap:
        tap = CoreTap(self, msg_type, resolve_name(topic), callback, qos_profile)
        self._taps.append(tap)
        return tap

    def destroy_subscription(self, tap: CoreTap) -> None:
        if tap in self._taps:
            self._taps.remove(tap)
            tap.close()

    def create_service(self, srv_type: type[ServiceType], srv_name: str, callback: Callable[..., Any]) -> Service:
        service = Service(srv_type, resolve_name(srv_name), callback)
        self.guest.serves(service)
        self._services.append(service.name)
        return service

    def close(self) -> None:
        """End every publication, reading and service this host made."""
        for publisher in self._publishers:
            publisher.close()
        for tap in self._taps:
            tap.close()
        for name in self._services:
            self.guest.stops_serving(name)
        self._publishers.clear()
        self._taps.clear()
        self._services.clear()
