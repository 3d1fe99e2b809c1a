"""The Foxglove WebSocket protocol: Foxglove and Lichtblick on the core's one topic edge.

    ws://CORE:8765/   (``--foxglove-port``; 0 turns it off)
    subprotocols foxglove.websocket.v1 and foxglove.sdk.v1

On connect a client gets ``serverInfo`` and an ``advertise`` of every topic whose type the core
knows (JSON encoding, JSON schema, ROS type names: see :mod:`.foxglove_schema`), and of every
service; both follow the graph as it changes. Subscribing reads the topic through the
connection's :class:`~services.core.protocols.session.ClientSession`; messages arrive as binary
``0x01`` frames whose payload is made once for every connection. Clients publish (advertise,
then ``0x01`` client frames), call services (``0x02`` -> ``0x03`` or ``serviceCallFailure``),
get, set and follow parameters (:mod:`.parameters`, named ``/node.param``), and follow the
connection graph. While a simulator publishes ``/clock``, the server offers ``time``: ``0x02``
time frames from ``/clock``, and message timestamps on the same clock.

A bad request is answered with a ``status`` (level 2, error) for that request only. A client
that stops reading is closed with 4001 (see :mod:`.session`).
"""

from __future__ import annotations

import asyncio
import json
import logging
import struct
import time
from collections.abc import Callable, Sequence
from typing import Any

from starlette.websockets import WebSocket

from services.core.gateway_topic import declared_type
from services.core.protocols.access import CoreAccess
from services.core.protocols.foxglove_graph import GraphView
from services.core.protocols.foxglove_schema import (
    Payloads,
    channel_schema,
    publishable_text,
    service_schemas,
)
from services.core.protocols.parameters import (
    ParameterError,
    Parameters,
    ParameterValueJson,
    event_values,
)
from services.core.protocols.rosapi import ROS_DISTRO
from services.core.protocols.session import ClientSession, incoming
from services.core.service_calls import ServiceCallFailed
from services.runtime.edge.frames import FrameRejected, close_with
from services.runtime.wire import DEFAULT_QUEUE, Close
from shared_models import InvalidNameError, Message, resolve_name
from shared_models.builtin_interfaces import Time
from shared_models.errors import SkydeckError

__all__ = ["SUBPROTOCOLS", "FoxgloveEndpoint"]

logger = logging.getLogger("skydeck.foxglove")

SUBPROTOCOLS = ("foxglove.websocket.v1", "foxglove.sdk.v1")
_CAPABILITIES = ["clientPublish", "parameters", "parametersSubscribe", "services", "connectionGraph"]
_INFO, _WARNING, _ERROR = 0, 1, 2
_CLOCK, _PARAMETER_EVENTS = "/clock", "/parameter_events"
_MESSAGE_DATA, _TIME, _SERVICE_RESPONSE = 1, 2, 3  # server -> client binary opcodes
_CLIENT_MESSAGE, _SERVICE_REQUEST = 1, 2  # client -> server binary opcodes
_MAX_CALLS_IN_FLIGHT = 256


class _Refused(SkydeckError):
    """A request that cannot be carried out: answered with a status, nothing else happens."""


class FoxgloveEndpoint:
    """Serves Foxglove connections; payloads and channel ids are shared by all of them."""

    def __init__(self, access: CoreAccess) -> None:
        self.access = access
        self.payloads = Payloads()
        self.graph = GraphView(access.registry)
        self.session_id = str(time.time_ns())
        self._connections: set[_Connection] = set()
        self._refresh_pending = False
        self._unwatch = access.registry.watch(self._graph_changed)

    async def serve(self, websocket: WebSocket) -> None:
        """One Foxglove connection, from handshake to close."""
        offered = websocket.scope.get("subprotocols", [])
        chosen = next((p for p in offered if p in SUBPROTOCOLS), None)
        if chosen is None:
            await websocket.accept()
            await close_with(
                websocket, Close.POLICY, "this is a Foxglove WebSocket endpoint: offer the subprotocol foxglove.websocket.v1"
            )
            return
        await websocket.accept(subprotocol=chosen)
        session = self.access.session(websocket, "foxglove")
        connection = _Connection(self, session)
        self._connections.add(connection)
        try:
            stalled = await session.serve(connection.run(websocket), advice="subscribe to fewer channels")
        finally:
            self._connections.discard(connection)
            connection.close()
        if stalled is not None:
            await close_with(websocket, stalled.code, stalled.reason)

    def close(self) -> None:
        self._unwatch()

    def _graph_changed(self) -> None:
        # Many registry changes come at once (a launch, a client subscribing): refresh once.
        if self._refresh_pending or not self._connections:
            return
        self._refresh_pending = True
        asyncio.get_running_loop().call_soon(self._refresh)

    def _refresh(self) -> None:
        self._refresh_pending = False
        self.graph.update()
        for connection in list(self._connections):
            connection.spawn(connection.follow_graph())


class _Connection:
    """One client: its channels, subscriptions, publications, parameters and calls."""

    def __init__(self, endpoint: FoxgloveEndpoint, session: ClientSession) -> None:
        self._endpoint = endpoint
        self._session = session
        self._access = endpoint.access
        self._channels: dict[int, tuple[str, type[Message]]] = {}  # advertised to the client
        self._services: dict[int, tuple[str, str]] = {}  # id -> (name, type)
        self._subscriptions: dict[int, tuple[str, type[Message]]] = {}  # id -> (topic, type)
        self._subscribed_topics: dict[str, int] = {}  # topic -> subscription id
        self._client_channels: dict[int, str] = {}  # client channel id -> topic
        self._parameters = Parameters(self._access.registry, session.call)
        self._parameter_names: set[str] = set()
        self._all_parameters = False
        self._graph_subscribed = False
        self._graph_sent: dict[str, Any] | None = None
        self._uses_time = bool(self._access.registry.publishers(_CLOCK))
        self._sim_ns = 0
        self._tasks: set[asyncio.Task[Any]] = set()
        self._ops: dict[str, Callable[[dict[str, Any]], Any]] = {
            "subscribe": self._subscribe,
            "unsubscribe": self._unsubscribe,
            "advertise": self._advertise,
            "unadvertise": self._unadvertise,
            "getParameters": self._get_parameters,
            "setParameters": self._set_parameters,
            "subscribeParameterUpdates": self._subscribe_parameters,
            "unsubscribeParameterUpdates": self._unsubscribe_parameters,
            "subscribeConnectionGraph": self._subscribe_graph,
            "unsubscribeConnectionGraph": self._unsubscribe_graph,
        }

    # -- the connection ---------------------------------------------------------------------------

    async def run(self, websocket: WebSocket) -> None:
        capabilities = _CAPABILITIES + (["time"] if self._uses_time else [])
        await self._send({
            "op": "serverInfo",
            "name": "Skydeck",
            "capabilities": capabilities,
            "supportedEncodings": ["json"],
            "metadata": {"ROS_DISTRO": ROS_DISTRO, "skydeck_core": self._access.core.participant.url},
            "sessionId": self._endpoint.session_id,
        })
        self._endpoint.graph.update()
        await self.follow_graph()
        if self._uses_time:
            self._follow(_CLOCK)
        limit = self._access.settings.max_message_bytes
        async for frame in incoming(websocket, limit):
            try:
                if frame is None:
                    raise _Refused(f"a message of over {limit} bytes is refused (SKYDECK_MAX_MESSAGE_BYTES)")
                if isinstance(frame, bytes):
                    self._binary(frame)
                else:
                    await self._json(frame)
            except (_Refused, SkydeckError) as error:
                await self._status(_ERROR, str(error))

    def close(self) -> None:
        for task in self._tasks:
            task.cancel()
        self._session.close()

    def spawn(self, coroutine: Any) -> None:
        task = asyncio.get_running_loop().create_task(coroutine)
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    async def _send(self, message: dict[str, Any]) -> None:
        await self._session.send_text(json.dumps(message))

    async def _status(self, level: int, text: str) -> None:
        await self._send({"op": "status", "level": level, "message": text})

    async def _json(self, text: str) -> None:
        try:
            request = json.loads(text)
        except ValueError as error:
            raise _Refused(f"not JSON: {error}") from None
        if not isinstance(request, dict) or not isinstance(request.get("op"), str):
            raise _Refused('a Foxglove message is a JSON object with an "op"')
        handler = self._ops.get(request["op"])
        if handler is None:
            raise _Refused(f"unknown op {request['op']!r}: this server handles {', '.join(self._ops)}")
        result = handler(request)
        if asyncio.iscoroutine(result):
            await result

    def _binary(self, data: bytes) -> None:
        if not data:
            raise _Refused("an empty binary message has no opcode")
        if data[0] == _CLIENT_MESSAGE and len(data) >= 5:
            (channel,) = struct.unpack_from("<I", data, 1)
            self._publish(channel, data[5:])
        elif data[0] == _SERVICE_REQUEST and len(data) >= 13:
            service, call, length = struct.unpack_from("<III", data, 1)
            encoding = data[13 : 13 + length].decode(errors="replace")
            self._call(service, call, encoding, data[13 + length :])
        else:
            raise _Refused(f"binary opcode {data[0]:#04x} is not a client message (0x01) or service call (0x02)")

    # -- channels ---------------------------------------------------------------------------------

    async def follow_graph(self) -> None:
        """Advertise what appeared since the last call and unadvertise what went away."""
        graph = self._endpoint.graph
        # The state changes before the first await: a call running meanwhile sees it.
        removed = [cid for cid in self._channels if cid not in graph.channels]
        added = [cid for cid in graph.channels if cid not in self._channels]
        for cid in removed:
            topic, _ = self._channels.pop(cid)
            if topic in self._subscribed_topics:
                self._drop_subscription(self._subscribed_topics[topic])
        self._channels.update({cid: graph.channels[cid] for cid in added})
        gone = [sid for sid in self._services if sid not in graph.services]
        new = [sid for sid in graph.services if sid not in self._services]
        for sid in gone:
            del self._services[sid]
        self._services.update({sid: graph.services[sid][:2] for sid in new})
        if removed:
            await self._send({"op": "unadvertise", "channelIds": removed})
        if added:
            await self._send({"op": "advertise", "channels": [self._channel(cid) for cid in added]})
        if gone:
            await self._send({"op": "unadvertiseServices", "serviceIds": gone})
        if new:
            services = graph.services
            await self._send({
                "op": "advertiseServices",
                "services": [
                    {"id": sid, "name": services[sid][0], "type": services[sid][1], **service_schemas(services[sid][2])}
                    for sid in new
                    if sid in services
                ],
            })
        if self._graph_subscribed:
            await self._send_graph()

    def _channel(self, cid: int) -> dict[str, Any]:
        topic, msg_type = self._channels[cid]
        return {
            "id": cid,
            "topic": topic,
            "encoding": "json",
            "schemaName": msg_type.__ros_type__,
            "schema": channel_schema(msg_type),
            "schemaEncoding": "jsonschema",
        }

    def _subscribe(self, request: dict[str, Any]) -> None:
        for item in _items(request, "subscriptions"):
            sub_id, cid = _uint(item, "id"), _uint(item, "channelId")
            if sub_id in self._subscriptions:
                raise _Refused(f"subscription id {sub_id} is in use: unsubscribe it first")
            if cid not in self._channels:
                raise _Refused(f"no channel {cid}: subscribe to a channel the server advertised")
            topic = self._channels[cid][0]
            if topic in self._subscribed_topics:
                raise _Refused(f"channel {cid} ({topic}) is subscribed already (subscription {self._subscribed_topics[topic]})")
            self._subscriptions[sub_id] = self._channels[cid]
            self._subscribed_topics[topic] = sub_id
            self._follow(topic)

    def _unsubscribe(self, request: dict[str, Any]) -> None:
        ids = request.get("subscriptionIds")
        if not isinstance(ids, list):
            raise _Refused("unsubscribe needs subscriptionIds: a list of numbers")
        unknown = [sub_id for sub_id in ids if sub_id not in self._subscriptions]
        for sub_id in ids:
            if sub_id in self._subscriptions:
                self._drop_subscription(sub_id)
        if unknown:
            raise _Refused(f"no subscription {unknown}")

    def _drop_subscription(self, sub_id: int) -> None:
        topic, _ = self._subscriptions.pop(sub_id)
        del self._subscribed_topics[topic]
        self._follow(topic)

    def _follow(self, topic: str) -> None:
        """Read ``topic`` while anything of this connection needs it: a subscription, the time
        (``/clock``), parameter updates (``/parameter_events``)."""
        wanted = (
            topic in self._subscribed_topics
            or (topic == _CLOCK and self._uses_time)
            or (topic == _PARAMETER_EVENTS and (self._parameter_names or self._all_parameters))
        )
        reading = self._session.readings.get(topic)
        if not wanted:
            self._session.stop_reading(topic)
        elif reading is None:
            self._session.start_reading(topic, queue=DEFAULT_QUEUE, encode=self._encoder(topic))

    def _encoder(self, topic: str) -> Callable[[str], Sequence[dict[str, Any]]]:
        payloads = self._endpoint.payloads

        def encode(frame: str) -> Sequence[dict[str, Any]]:
            messages: list[dict[str, Any]] = []
            if topic == _CLOCK and self._uses_time:
                self._sim_ns = _clock_ns(frame, self._sim_ns)
                messages.append({"type": "websocket.send", "bytes": struct.pack("<BQ", _TIME, self._sim_ns)})
            if topic == _PARAMETER_EVENTS:
                messages += self._parameter_update(frame)
            sub_id = self._subscribed_topics.get(topic)
            if sub_id is not None:
                _, msg_type = self._subscriptions[sub_id]
                now = self._sim_ns if self._uses_time else time.time_ns()
                data = struct.pack("<BIQ", _MESSAGE_DATA, sub_id, now) + payloads.payload(topic, msg_type, frame)
                messages.append({"type": "websocket.send", "bytes": data})
            return messages

        return encode

    # -- client publishing ------------------------------------------------------------------------

    def _advertise(self, request: dict[str, Any]) -> None:
        self._session.check_may_write()
        for item in _items(request, "channels"):
            cid = _uint(item, "id")
            if item.get("encoding") != "json":
                raise _Refused(f"channel {cid}: encoding {item.get('encoding')!r} is not supported: use json")
            try:
                topic = resolve_name(str(item.get("topic", "")))
            except InvalidNameError as error:
                raise _Refused(f"channel {cid}: {error}") from None
            schema_name = item.get("schemaName")
            try:
                self._session.declare(topic, declared_type(schema_name if isinstance(schema_name, str) else None))
            except FrameRejected as error:
                raise _Refused(f"channel {cid} ({topic}): {error.reason}") from None
            self._client_channels[cid] = topic

    def _unadvertise(self, request: dict[str, Any]) -> None:
        ids = request.get("channelIds")
        if not isinstance(ids, list):
            raise _Refused("unadvertise needs channelIds: a list of numbers")
        for cid in ids:
            topic = self._client_channels.pop(cid, None)
            if topic is not None and topic not in self._client_channels.values():
                self._session.stop_publishing(topic)

    def _publish(self, cid: int, payload: bytes) -> None:
        topic = self._client_channels.get(cid)
        if topic is None:
            raise _Refused(f"no client channel {cid}: advertise it first")
        try:
            text = publishable_text(payload)
        except ValueError as error:
            raise _Refused(f"channel {cid} ({topic}): the payload is not JSON text: {error}") from None
        try:
            self._session.publish(topic, text)
        except FrameRejected as error:
            raise _Refused(f"channel {cid} ({topic}): {error.reason}") from None

    # -- services ---------------------------------------------------------------------------------

    def _call(self, service_id: int, call_id: int, encoding: str, payload: bytes) -> None:
        if service_id not in self._services:
            raise _Refused(f"no service {service_id}: call a service the server advertised")
        if len(self._tasks) >= _MAX_CALLS_IN_FLIGHT:
            raise _Refused(f"{_MAX_CALLS_IN_FLIGHT} calls are already in flight on this connection")
        self.spawn(self._answer(service_id, call_id, encoding, payload))

    async def _answer(self, service_id: int, call_id: int, encoding: str, payload: bytes) -> None:
        name = self._services[service_id][0]
        try:
            if encoding != "json":
                raise _Refused(f"encoding {encoding!r} is not supported: use json")
            reply = await self._session.call(name, payload)
            if not reply.answered:
                raise _Refused(reply.detail())
        except (_Refused, ServiceCallFailed) as error:
            await self._send({"op": "serviceCallFailure", "serviceId": service_id, "callId": call_id, "message": str(error)})
            return
        header = struct.pack("<BIII", _SERVICE_RESPONSE, service_id, call_id, 4) + b"json"
        await self._session.send_bytes(header + reply.body)

    # -- parameters -------------------------------------------------------------------------------

    async def _get_parameters(self, request: dict[str, Any]) -> None:
        names = request.get("parameterNames") or None
        if names is not None and not (isinstance(names, list) and all(isinstance(n, str) for n in names)):
            raise _Refused("getParameters needs parameterNames: a list of strings")
        try:
            values = await self._parameters.get(names)
        except ParameterError as error:
            await self._status(_ERROR, str(error))
            values = []
        await self._send_parameters(values, request.get("id"))

    async def _set_parameters(self, request: dict[str, Any]) -> None:
        self._session.check_may_write()
        items = [
            ParameterValueJson(str(item.get("name", "")), item.get("value"), item.get("type"))
            for item in _items(request, "parameters")
        ]
        try:
            results = await self._parameters.set(items)
        except ParameterError as error:
            raise _Refused(str(error)) from None
        for name, successful, reason in results:
            if not successful:
                await self._status(_ERROR, f"{name} was not set: {reason}")
        if request.get("id") is not None:
            try:
                values = await self._parameters.get([item.name for item in items])
            except ParameterError:
                values = []
            await self._send_parameters(values, request["id"])

    async def _send_parameters(self, values: list[ParameterValueJson], request_id: Any) -> None:
        message: dict[str, Any] = {"op": "parameterValues", "parameters": [_parameter(v) for v in values]}
        if request_id is not None:
            message["id"] = request_id
        await self._send(message)

    def _subscribe_parameters(self, request: dict[str, Any]) -> None:
        names = request.get("parameterNames") or []
        if not isinstance(names, list):
            raise _Refused("subscribeParameterUpdates needs parameterNames: a list of strings")
        if names:
            self._parameter_names.update(str(name) for name in names)
        else:
            self._all_parameters = True
        self._follow(_PARAMETER_EVENTS)

    def _unsubscribe_parameters(self, request: dict[str, Any]) -> None:
        names = request.get("parameterNames") or []
        if names:
            self._parameter_names.difference_update(str(name) for name in names)
        else:
            self._parameter_names.clear()
            self._all_parameters = False
        self._follow(_PARAMETER_EVENTS)

    def _parameter_update(self, frame: str) -> list[dict[str, Any]]:
        try:
            values = event_values(frame)
        except ValueError:
            return []
        wanted = [v for v in values if self._all_parameters or v.name in self._parameter_names]
        if not wanted:
            return []
        text = json.dumps({"op": "parameterValues", "parameters": [_parameter(v) for v in wanted]})
        return [{"type": "websocket.send", "text": text}]

    # -- the connection graph ---------------------------------------------------------------------

    async def _subscribe_graph(self, request: dict[str, Any]) -> None:
        self._graph_subscribed = True
        self._graph_sent = None
        await self._send_graph()

    def _unsubscribe_graph(self, request: dict[str, Any]) -> None:
        self._graph_subscribed = False

    async def _send_graph(self) -> None:
        update = self._endpoint.graph.connection_graph(self._graph_sent)
        self._graph_sent = self._endpoint.graph.graph_state()
        if update is not None:
            await self._send(update)


def _parameter(value: ParameterValueJson) -> dict[str, Any]:
    entry: dict[str, Any] = {"name": value.name, "value": value.value}
    if value.type is not None:
        entry["type"] = value.type
    return entry


def _items(request: dict[str, Any], key: str) -> list[dict[str, Any]]:
    items = request.get(key)
    if not isinstance(items, list) or not all(isinstance(item, dict) for item in items):
        raise _Refused(f"{request['op']} needs {key}: a list of objects")
    return items


def _uint(item: dict[str, Any], key: str) -> int:
    value = item.get(key)
    if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value < 2**32:
        raise _Refused(f"{key} must be an integer 0..2^32-1, got {value!r}")
    return value


def _clock_ns(frame: str, previous: int) -> int:
    """The time a ``/clock`` frame says (a builtin_interfaces Time, or a rosgraph_msgs Clock)."""
    try:
        value = json.loads(frame)
        return Time.model_validate(value.get("clock", value)).to_nsec()
    except (ValueError, AttributeError):
        return previous

