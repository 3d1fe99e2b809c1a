"""Topics across the bridge, both ways, each message once.

Out (Skydeck -> ROS 2): every Skydeck topic another Skydeck node publishes gets a DDS writer of
the same name and type at once (so ``ros2 topic list`` shows it); the bridge reads it in Skydeck
(a raw subscription in msgpack: each frame as the link carries it, never made into a message)
from the moment a ROS 2 reader is there, and writes each frame as CDR (``publish(bytes)``).

In (ROS 2 -> Skydeck): every ROS 2 topic another DDS participant writes gets a Skydeck publisher
of the same name and type at once (so ``skydeck topic list`` shows it); the bridge reads it on
DDS (a raw subscription, QoS matching the writers) from the moment a Skydeck reader is there, or
at once if the writers latch, and publishes each message (made from the CDR, validated: NaN
and infinity, which ROS 2 allows and Skydeck refuses, drop that message with one warning).

No loops, no duplicates: a frame the bridge publishes in Skydeck reaches its own raw
subscription at once (the endpoint hands it to its taps inside ``publish``), and is skipped
there; a DDS message the bridge's own writers sent is skipped by its writer's GUID prefix. A
topic only the bridge publishes on a side is not bridged back to the other.
"""

from __future__ import annotations

import asyncio
import logging
import re
from typing import Any

import ormsgpack
from pydantic import ValidationError

from services.protocols.ros2.dds import DdsSide, RosGraph, publisher_qos, subscription_qos
from services.protocols.ros2.types import MessageMapping, NotBridged, message_mapping
from services.runtime import Node
from services.runtime.publisher import Publisher
from shared_models.cdr import CdrError
from shared_models.ros2msg import ros2_type_name, skydeck_type_name

__all__ = ["TopicBridge"]

logger = logging.getLogger("skydeck.ros2")

# ROS 2's own plumbing, never a Skydeck topic.
_ROS_ONLY = re.compile(r"^/(parameter_events|rosout)$")


class _Out:
    """A Skydeck topic written on DDS."""

    def __init__(self, topic: str, mapping: MessageMapping, writer: Any) -> None:
        self.topic = topic
        self.mapping = mapping
        self.writer = writer
        self.reading = False
        self.failed = False

    def send(self, frame: bytes) -> None:
        try:
            self.writer.publish(self.mapping.to_ros(ormsgpack.unpackb(frame)))
        except (CdrError, ValueError, ormsgpack.MsgpackDecodeError) as error:
            if not self.failed:
                self.failed = True
                logger.warning("not bridged to ROS 2, a message on %s: %s", self.topic, error)


class _In:
    """A ROS 2 topic published in Skydeck."""

    def __init__(self, topic: str, mapping: MessageMapping, publisher: Publisher[Any], latched: bool) -> None:
        self.topic = topic
        self.mapping = mapping
        self.publisher = publisher
        self.latched = latched
        self.reader: Any = None
        self.warned = False


class TopicBridge:
    """Both directions of every topic whose name matches ``pattern``."""

    def __init__(self, node: Node, dds: DdsSide, pattern: re.Pattern[str]) -> None:
        self._node = node
        self._dds = dds
        self._pattern = pattern
        self._loop = asyncio.get_running_loop()
        self._out: dict[str, _Out] = {}
        self._in: dict[str, _In] = {}
        self._refused: set[str] = set()
        self._sending_in: str | None = None  # the topic whose frame the bridge is publishing now

    # -- the graphs, twice a second ------------------------------------------------------------------

    def sync(self, skydeck: dict[str, Any], ros: RosGraph) -> None:
        me = self._node.get_name()
        for topic in skydeck["topics"]:
            name, kind = topic["name"], topic["type"]
            others = [p for p in topic["publishers"] if p != me and p not in self._foreign_names(skydeck)]
            if not kind or not others or not self._pattern.search(name):
                continue
            out = self._out.get(name) or self._open_out(name, kind, topic.get("latched", False))
            if out is not None and not out.reading and ros.subscribers.get(name):
                self._read_skydeck(out)
        for name, types in ros.topics.items():
            writers = ros.publishers.get(name, [])
            if not writers or not self._pattern.search(name) or _ROS_ONLY.match(name):
                continue
            inbound = self._in.get(name) or self._open_in(name, types[0], writers)
            if inbound is not None and inbound.reader is None and (inbound.latched or self._node_reads(name)):
                self._read_dds(inbound, writers)

    @staticmethod
    def _foreign_names(skydeck: dict[str, Any]) -> set[str]:
        return {n["name"] for n in skydeck["nodes"] if n.get("system")}

    def _refuse(self, topic: str, reason: str) -> None:
        if topic not in self._refused:
            self._refused.add(topic)
            logger.warning("skydeck: not bridging %s: %s", topic, reason)

    # -- out: Skydeck -> ROS 2 ---------------------------------------------------------------------

    def _open_out(self, topic: str, kind: str, latched: bool) -> _Out | None:
        try:
            mapping = message_mapping(kind, ros2_type_name(topic, kind))
            writer = self._dds.node.create_publisher(mapping.ros_cls, topic, publisher_qos(latched))
        except NotBridged as error:
            if not error.quiet:
                self._refuse(topic, str(error))
            return None
        except Exception as error:  # noqa: BLE001 - rclpy's own refusals (a name it rejects)
            self._refuse(topic, f"ROS 2 refused it: {error}")
            return None
        out = self._out[topic] = _Out(topic, mapping, writer)
        logger.info("bridging %s to ROS 2 as %s", topic, mapping.ros_name)
        return out

    def _read_skydeck(self, out: _Out) -> None:
        out.reading = True

        def frame(packed: bytes) -> None:
            if self._sending_in != out.topic:  # not the bridge's own publication
                out.send(packed)

        # msgpack, as links carry it: a camera's bytes stay bytes (JSON's base64 cost 80x more)
        self._node.create_subscription(out.mapping.skydeck, out.topic, frame, 100, raw=True, raw_encoding="msgpack")

    # -- in: ROS 2 -> Skydeck ----------------------------------------------------------------------

    def _open_in(self, topic: str, ros_type: str, writers: list[Any]) -> _In | None:
        try:
            mapping = message_mapping(skydeck_type_name(topic, ros_type), ros_type)
        except NotBridged as error:
            self._refuse(topic, str(error))
            return None
        _, latched = subscription_qos(writers)
        publisher = self._node.create_publisher(mapping.skydeck, topic, 10, latched=latched)
        inbound = self._in[topic] = _In(topic, mapping, publisher, latched)
        logger.info("bridging %s from ROS 2 (%s)", topic, ros_type)
        return inbound

    def _node_reads(self, topic: str) -> bool:
        endpoint = self._node._participant.endpoints.get(topic)  # noqa: SLF001 - the bridge is the node
        return endpoint is not None and endpoint.read

    def _read_dds(self, inbound: _In, writers: list[Any]) -> None:
        qos, _ = subscription_qos(writers)
        loop, dds = self._loop, self._dds

        def received(data: bytes, info: Any) -> None:  # on an executor thread
            gid = (info.get("publisher_gid") or {}).get("data")
            if not dds.is_own(gid):
                loop.call_soon_threadsafe(self._deliver, inbound, data)

        inbound.reader = dds.node.create_subscription(inbound.mapping.ros_cls, inbound.topic, received, qos, raw=True)

    def _deliver(self, inbound: _In, data: bytes) -> None:
        try:
            message = inbound.mapping.skydeck.model_validate(inbound.mapping.from_ros(data))
        except (CdrError, ValidationError) as error:
            if not inbound.warned:
                inbound.warned = True
                reason = str(error).splitlines()[0] if isinstance(error, CdrError) else _first_error(error)
                logger.warning("dropped a message on %s from ROS 2 (said once): %s", inbound.topic, reason)
            return
        self._sending_in = inbound.topic
        try:  # the model: serialised once per encoding its readers want (msgpack: bytes as bytes)
            inbound.publisher.publish(message)
        finally:
            self._sending_in = None


def _first_error(error: ValidationError) -> str:
    """The first of a message's validation errors, with where it is (NaN and infinity, which
    ROS 2 allows and Skydeck's messages refuse, are the usual one)."""
    first = error.errors(include_url=False)[0]
    where = ".".join(str(part) for part in first["loc"])
    return f"{where}: {first['msg']}"
