"""The bridge's DDS side: one real rclpy node on its own context and executor thread.

rclpy's executors run callbacks on their threads; everything the bridge does with a message
happens on Skydeck's event loop, so each callback hands its bytes over with
``call_soon_threadsafe`` and returns. Publishing (``publish(bytes)``) and rclpy's graph queries
are safe from the loop's thread.

Two rclpy nodes share the one participant (context): ``node`` carries the topics on a
single-threaded executor (a message's way through it is shortest there: a multi-threaded
executor's hand-over to its pool cost the bridge half its inbound rate and doubled its latency),
``service_node`` the services on a multi-threaded one, where a call may block a thread while
Skydeck answers it.

The participant's GUID prefix (the first 12 bytes of every endpoint's gid) tells the bridge's
own DDS writers from others: a message the bridge itself sent out is never taken back in.
"""

from __future__ import annotations

import contextlib
import threading
from dataclasses import dataclass, field
from typing import Any

import rclpy
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.context import Context
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node as RclpyNode
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

__all__ = ["DdsSide", "Endpoint", "RosGraph", "publisher_qos", "subscription_qos"]

_SERVICE_THREADS = 4  # service calls block a thread each while Skydeck answers


def publisher_qos(latched: bool) -> QoSProfile:
    """A Skydeck topic's writer: reliable (links are TCP); latched is transient-local, depth 1."""
    if latched:
        return QoSProfile(
            history=HistoryPolicy.KEEP_LAST, depth=1, reliability=ReliabilityPolicy.RELIABLE,
            durability=DurabilityPolicy.TRANSIENT_LOCAL,
        )
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=10, reliability=ReliabilityPolicy.RELIABLE)


def subscription_qos(publishers: list[Endpoint]) -> tuple[QoSProfile, bool]:
    """A reader that matches every writer of a topic, and whether the topic is latched.

    Best effort if any writer is (a reliable reader would not match it); transient-local only if
    every writer is (it would not match a volatile one), which is when Skydeck latches it."""
    best_effort = any(p.reliable is False for p in publishers)
    latched = bool(publishers) and all(p.transient_local for p in publishers)
    return QoSProfile(
        history=HistoryPolicy.KEEP_LAST,
        depth=1 if latched else 10,
        reliability=ReliabilityPolicy.BEST_EFFORT if best_effort else ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE,
    ), latched


@dataclass(frozen=True)
class Endpoint:
    """One writer or reader of a topic: its node, whether it is ours, its QoS."""

    node: str
    ours: bool
    reliable: bool
    transient_local: bool


@dataclass
class RosGraph:
    """What the DDS side sees, the bridge's own entities left out."""

    # topic -> types, writers, readers
    topics: dict[str, list[str]] = field(default_factory=dict)
    publishers: dict[str, list[Endpoint]] = field(default_factory=dict)
    subscribers: dict[str, list[Endpoint]] = field(default_factory=dict)
    # service -> types (services some other node serves)
    services: dict[str, list[str]] = field(default_factory=dict)
    # node -> (publications, subscriptions, services) with types
    nodes: dict[str, tuple[list[tuple[str, str]], list[tuple[str, str]], list[tuple[str, str]]]] = field(default_factory=dict)


class DdsSide:
    """The rclpy node ``name`` on DDS domain ``domain``, spun on threads of its own."""

    def __init__(self, name: str, domain: int) -> None:
        self.domain = domain
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain, args=[])
        self.node = RclpyNode(name, context=self.context, start_parameter_services=False)
        self.service_node = RclpyNode(f"{name}_services", context=self.context, start_parameter_services=False)
        self.name = self.node.get_fully_qualified_name()
        self.own_nodes = {self.name, self.service_node.get_fully_qualified_name()}
        self.group = ReentrantCallbackGroup()  # the services'
        self._executors = [SingleThreadedExecutor(context=self.context), MultiThreadedExecutor(num_threads=_SERVICE_THREADS, context=self.context)]
        self._executors[0].add_node(self.node)
        self._executors[1].add_node(self.service_node)
        self._threads = [
            threading.Thread(target=self._spin, args=(executor,), name=f"ros2-{kind}", daemon=True)
            for executor, kind in zip(self._executors, ("topics", "services"), strict=True)
        ]
        self._prefix: bytes | None = None

    def start(self) -> None:
        # Every rclpy node writes /rosout: its gid gives the participant's prefix at once.
        for info in self.node.get_publishers_info_by_topic("/rosout"):
            self._endpoint(info)
        for thread in self._threads:
            thread.start()

    @staticmethod
    def _spin(executor: Any) -> None:
        with contextlib.suppress(ExternalShutdownException):
            executor.spin()

    def stop(self) -> None:
        for executor in self._executors:
            executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        self.service_node.destroy_node()
        if self.context.ok():
            rclpy.shutdown(context=self.context)
        for thread in self._threads:
            thread.join(timeout=2.0)

    # -- own writers ------------------------------------------------------------------------------

    def is_own(self, gid: bytes | None) -> bool:
        """Whether a message's writer (its gid, from MessageInfo) is one of the bridge's."""
        return gid is not None and self._prefix is not None and bytes(gid[:12]) == self._prefix

    def _learn_prefix(self, gid: list[int]) -> None:
        if self._prefix is None and gid:
            self._prefix = bytes(gid[:12])

    # -- the graph --------------------------------------------------------------------------------

    def graph(self) -> RosGraph:
        node = self.node
        graph = RosGraph()
        for topic, types in node.get_topic_names_and_types():
            writers = [self._endpoint(i) for i in node.get_publishers_info_by_topic(topic)]
            readers = [self._endpoint(i) for i in node.get_subscriptions_info_by_topic(topic)]
            graph.topics[topic] = types
            graph.publishers[topic] = [w for w in writers if not w.ours]
            graph.subscribers[topic] = [r for r in readers if not r.ours]
        own_services = {
            name for name, _ in self.service_node.get_service_names_and_types_by_node(
                self.service_node.get_name(), self.service_node.get_namespace()
            )
        }
        for service, types in node.get_service_names_and_types():
            if service not in own_services:
                graph.services[service] = types
        for name, namespace in node.get_node_names_and_namespaces():
            full = (namespace.rstrip("/") + "/" + name) if namespace else "/" + name
            if full in self.own_nodes:
                continue
            try:
                graph.nodes[full] = (
                    [(t, ts[0]) for t, ts in node.get_publisher_names_and_types_by_node(name, namespace)],
                    [(t, ts[0]) for t, ts in node.get_subscriber_names_and_types_by_node(name, namespace)],
                    [(s, ts[0]) for s, ts in node.get_service_names_and_types_by_node(name, namespace)],
                )
            except Exception:  # noqa: BLE001 - a node that left between the two calls
                continue
        return graph

    def _endpoint(self, info: Any) -> Endpoint:
        full = (info.node_namespace.rstrip("/") + "/" + info.node_name) if info.node_namespace else "/" + info.node_name
        ours = full in self.own_nodes
        if ours:
            self._learn_prefix(list(info.endpoint_gid))
        qos = info.qos_profile
        return Endpoint(
            node=full,
            ours=ours,
            reliable=qos.reliability == ReliabilityPolicy.RELIABLE,
            transient_local=qos.durability == DurabilityPolicy.TRANSIENT_LOCAL,
        )

