"""Services across the bridge, both ways.

Into Skydeck: a service some ROS 2 node serves becomes a Skydeck service of the same name and
type, hosted by the bridge node (so ``POST /NAME`` through the core reaches it); each call goes
to the ROS 2 server with rclpy's client and its answer comes back.

Out of Skydeck: a service a Skydeck node serves becomes a ROS 2 service served by the bridge's
rclpy node; each request is called through Skydeck's one service path (the SDK's client) and
answered with the Skydeck node's response.

Requests and responses cross as CDR too: rclpy has no raw services, so its messages are made
from and read into bytes with ``rclpy.serialization`` (C code), and Skydeck's from Skydeck's codec.
A call that fails on the far side (no server, a timeout) is one line in the log; the caller gets
the failure its side knows (a 503/504 in Skydeck, ROS 2's client times out).
"""

from __future__ import annotations

import asyncio
import logging
import re
from typing import Any

from rclpy.serialization import deserialize_message, serialize_message

from services.protocols.ros2.dds import DdsSide, RosGraph
from services.protocols.ros2.types import MessageMapping, NotBridged, service_mappings
from services.runtime import Node, ServiceError, ServiceTimeoutError
from shared_models import Message, ServiceType
from shared_models.cdr import CdrError

__all__ = ["ServiceBridge"]

logger = logging.getLogger("skydeck.ros2")

_CALL_TIMEOUT_S = 10.0


class ServiceBridge:
    """Both directions of every service whose name matches ``pattern``."""

    def __init__(self, node: Node, dds: DdsSide, pattern: re.Pattern[str]) -> None:
        self._node = node
        self._dds = dds
        self._pattern = pattern
        self._loop = asyncio.get_running_loop()
        self._in: dict[str, Any] = {}  # name -> rclpy client
        self._out: dict[str, Any] = {}  # name -> rclpy service
        self._refused_types: set[str] = set()
        self._skipped: set[str] = set()  # names whose type cannot cross: not looked at again

    def sync(self, skydeck: dict[str, Any], ros: RosGraph) -> None:
        me = self._node.get_name()
        for service in skydeck["services"]:
            name, kind = service["name"], service["type"]
            if service["node"] == me or name in self._out or name in self._skipped or name in ros.services or not self._pattern.search(name):
                continue
            self._serve_on_dds(name, kind)
        for name, types in ros.services.items():
            if name in self._in or name in self._out or name in self._skipped or not self._pattern.search(name):
                continue
            if any(s["name"] == name for s in skydeck["services"]):
                continue  # a Skydeck node serves it already
            self._serve_in_skydeck(name, types[0])

    def _mappings(self, name: str, kind: str) -> tuple[type[ServiceType], MessageMapping, MessageMapping] | None:
        try:
            return service_mappings(kind)
        except NotBridged as error:
            self._skipped.add(name)
            if kind not in self._refused_types and not error.quiet:
                self._refused_types.add(kind)
                logger.warning("skydeck: not bridging services of type %s (%s, ...): %s", kind, name, error)
            return None

    # -- ROS 2 -> Skydeck: a ROS 2 server answers Skydeck's callers ---------------------------------

    def _serve_in_skydeck(self, name: str, kind: str) -> None:
        mappings = self._mappings(name, kind)
        if mappings is None:
            return
        service_type, request_map, response_map = mappings
        ros_service = _ros_service_class(request_map)
        client: Any = self._dds.service_node.create_client(ros_service, name, callback_group=self._dds.group)
        self._in[name] = client

        async def handle(request: Message) -> Message:
            ros_request = deserialize_message(request_map.to_ros(request.model_dump()), request_map.ros_cls)
            future = client.call_async(ros_request)
            done: asyncio.Future[Any] = self._loop.create_future()
            future.add_done_callback(lambda f: _hand_over(self._loop, done, f))
            try:
                async with asyncio.timeout(_CALL_TIMEOUT_S):
                    ros_response = await done
            except TimeoutError:
                raise ServiceTimeoutError(
                    name, f"the ROS 2 server of {name} did not answer within {_CALL_TIMEOUT_S:g} s"
                ) from None
            return service_type.Response.model_validate(response_map.from_ros(serialize_message(ros_response)))

        self._node.create_service(service_type, name, handle)
        logger.info("bridging service %s from ROS 2 (%s)", name, kind)

    # -- Skydeck -> ROS 2: a Skydeck node answers ROS 2's callers -------------------------------------

    def _serve_on_dds(self, name: str, kind: str) -> None:
        mappings = self._mappings(name, kind)
        if mappings is None:
            return
        service_type, request_map, response_map = mappings
        skydeck_client = self._node.create_client(service_type, name)

        def answer(ros_request: Any, ros_response: Any) -> Any:  # on an executor thread
            try:
                request = service_type.Request.model_validate(request_map.from_ros(serialize_message(ros_request)))
                call = asyncio.run_coroutine_threadsafe(skydeck_client.call(request, timeout_s=_CALL_TIMEOUT_S), self._loop)
                response = call.result(timeout=_CALL_TIMEOUT_S + 1.0)
                return deserialize_message(response_map.to_ros(response.model_dump()), response_map.ros_cls)
            except (ServiceError, CdrError, ValueError, TimeoutError) as error:
                logger.warning("a ROS 2 call of %s was not answered by Skydeck: %s", name, error)
                return ros_response

        self._out[name] = self._dds.service_node.create_service(
            _ros_service_class(request_map), name, answer, callback_group=self._dds.group
        )
        logger.info("bridging service %s to ROS 2 (%s)", name, kind)


def _ros_service_class(request_map: MessageMapping) -> Any:
    """rclpy's service class of a request class (``Trigger_Request`` -> ``Trigger``)."""
    import importlib

    request_cls = request_map.ros_cls
    module = importlib.import_module(request_cls.__module__.rsplit(".", 1)[0])
    return getattr(module, request_cls.__name__.removesuffix("_Request"))


def _hand_over(loop: asyncio.AbstractEventLoop, done: asyncio.Future[Any], future: Any) -> None:
    """From rclpy's executor thread to the loop's (rclpy runs the callback on its thread)."""
    loop.call_soon_threadsafe(_settle, done, future)


def _settle(done: asyncio.Future[Any], future: Any) -> None:
    if done.done():
        return
    if future.exception() is not None:
        done.set_exception(future.exception())
    else:
        done.set_result(future.result())
