"""The bridge node: a Skydeck node and an rclpy node in one process, kept in step.

Twice a second it reads both graphs (the core's ``/api/graph``, rclpy's graph queries) and lets
the topic and service bridges open what appeared; the ROS 2 nodes it sees go into its
registration as foreign participants, so ``skydeck node list`` and the dashboard list them,
marked ROS 2. Its parameters say what it joined: ``domain_id``, ``topics``, ``services``.

    skydeck bridge ros2 --domain 0 --topics '^/(scan|cmd_vel|odom|tf|tf_static|clock)$'
"""

from __future__ import annotations

import logging
import os
import re
from typing import Any

from services.protocols.ros2.dds import DdsSide, RosGraph
from services.protocols.ros2.services import ServiceBridge
from services.protocols.ros2.topics import TopicBridge
from services.runtime import Node, NodeSettings
from services.runtime.protocol import Entity, ForeignNode
from shared_models.rcl_interfaces import ParameterDescriptor

__all__ = ["Ros2Bridge", "bridge_node_name"]

logger = logging.getLogger("skydeck.ros2")

_SYNC_PERIOD_S = 0.5


def bridge_node_name(domain: int) -> str:
    """One bridge per DDS domain in a Skydeck system: a second one takes the name (and the first
    stops), so two never carry the same messages twice."""
    return "ros2_bridge" if domain == 0 else f"ros2_bridge_{domain}"


class Ros2Bridge(Node):
    """Skydeck <-> ROS 2 on DDS domain ``domain``, for names matching ``topics``/``services``."""

    def __init__(
        self, domain: int, topics: str = ".*", services: str = ".*", *, discovery: str = "", settings: NodeSettings | None = None
    ) -> None:
        super().__init__(bridge_node_name(domain), settings=settings)
        read_only = ParameterDescriptor(read_only=True)
        self.declare_parameter("domain_id", domain, read_only)
        self.declare_parameter("topics", topics, read_only)
        self.declare_parameter("services", services, read_only)
        self.domain = domain
        self._discovery = discovery  # for the start-up line (Ros2Settings.discovery)
        self._topic_pattern = re.compile(topics)
        self._service_pattern = re.compile(services)
        self.dds: DdsSide | None = None
        self._topics: TopicBridge | None = None
        self._services: ServiceBridge | None = None
        self._last_error = ""
        self.create_timer(_SYNC_PERIOD_S, self._sync, wall_clock=True)

    async def start(self) -> None:
        self.dds = DdsSide(f"skydeck_bridge_{os.getpid()}", self.domain)
        self._topics = TopicBridge(self, self.dds, self._topic_pattern)
        self._services = ServiceBridge(self, self.dds, self._service_pattern)
        self.dds.start()
        await super().start()
        logger.info(
            "%s joined ROS 2 domain %d as %s (%s)", self.get_name(), self.domain, self.dds.name, self._discovery
        )

    async def stop(self) -> None:
        await super().stop()
        if self.dds is not None:
            self.dds.stop()

    async def _sync(self) -> None:
        if self.dds is None or self._topics is None or self._services is None:
            return
        reply = await self.http.get(f"{self.settings.core_url.rstrip('/')}/api/graph", timeout_s=5.0)
        if reply.status != 200:
            return
        skydeck: dict[str, Any] = reply.json()
        try:
            ros = self.dds.graph()
            self._topics.sync(skydeck, ros)
            self._services.sync(skydeck, ros)
        except Exception as error:  # noqa: BLE001 - one line, and the bridge carries on
            text = f"{type(error).__name__}: {error}"
            if text != self._last_error:
                self._last_error = text
                logger.warning("skydeck: the ROS 2 bridge could not follow the graph: %s", text)
            return
        self._update_foreign(ros)

    def _update_foreign(self, ros: RosGraph) -> None:
        foreign = [
            ForeignNode(
                name=name,
                system="ros2",
                publications=[Entity(name=t, type=k) for t, k in publications],
                subscriptions=[Entity(name=t, type=k) for t, k in subscriptions],
                services=[Entity(name=s, type=k) for s, k in services],
            )
            for name, (publications, subscriptions, services) in sorted(ros.nodes.items())
            if not name.startswith("/skydeck_bridge_")
        ]
        self.set_foreign_participants(foreign)
