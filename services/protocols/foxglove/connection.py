"""One Foxglove connection: its channels and subscriptions, its own channels, its service calls.

A connection advertises the graph's channels and services as they come and go
(:meth:`Connection.follow_graph`), reads a topic through its
:class:`~services.protocols.session.ClientSession` while a subscription, the time (``/clock``)
or parameter updates need it, and sends each message as a binary ``0x01`` frame around the
payload shared by every connection. A request that cannot be carried out gets a ``status``
(level 2) for that request alone.
"""

from __future__ import annotations

import asyncio
import json
import struct
import time
from collections.abc import Callable, Coroutine, Sequence
from dataclasses import dataclass
from typing import Any

from starlette.websockets import WebSocket

from services.access import AccessRefused, Forbidden, Pass, Verb, service_verb
from services.core.access import CoreAccess
from services.core.gateway_topic import declared_type
from services.core.service_calls import ServiceCallFailed
from services.protocols import ROS_DISTRO
from services.protocols.foxglove.graph import GraphView
from services.protocols.foxglove.ops import (
    CLIENT_MESSAGE,
    ERROR,
    MESSAGE_DATA,
    SERVICE_REQUEST,
    SERVICE_RESPONSE,
    TIME,
    Advertise,
    ConnectionGraph,
    GetParameters,
    ParameterUpdates,
    SetParameters,
    Subscribe,
    Unadvertise,
    Unsubscribe,
)
from services.protocols.foxglove.parameter_ops import PARAMETER_EVENTS, ParameterOps
from services.protocols.foxglove.payloads import (
    Payloads,
    channel,
    publishable_text,
    service_schemas,
)
from services.protocols.ops import JsonOps, Refused
from services.protocols.session import ClientSession, incoming
from services.runtime.edge.frames import FrameRejected
from services.runtime.wire import DEFAULT_QUEUE
from shared_models import InvalidNameError, Message, resolve_name
from shared_models.builtin_interfaces import Time
from shared_models.errors import SkydeckError

__all__ = ["Connection", "Shared"]

_CAPABILITIES = ["clientPublish", "parameters", "parametersSubscribe", "services", "connectionGraph"]
_CLOCK = "/clock"
_MAX_CALLS_IN_FLIGHT = 256


@dataclass(frozen=True)
class Shared:
    """What every connection of the endpoint shares: the core, payloads, the graph's ids."""

    access: CoreAccess
    payloads: Payloads
    graph: GraphView
    session_id: str


class Connection:
    """One client: its channels, subscriptions, publications, parameters and calls."""

    def __init__(self, shared: Shared, session: ClientSession) -> None:
        self._shared = shared
        self._session = session
        self._access = shared.access
        self._channels: dict[int, tuple[str, type[Message]]] = {}  # advertised to the client
        self._services: dict[int, tuple[str, str]] = {}  # id -> (name, type)
        self._subscriptions: dict[int, tuple[str, type[Message]]] = {}  # id -> (topic, type)
        self._subscribed_topics: dict[str, int] = {}  # topic -> subscription id
        self._client_channels: dict[int, str] = {}  # client channel id -> topic
        self._parameters = ParameterOps(session, self._send, lambda: self._follow(PARAMETER_EVENTS))
        self._graph_subscribed = False
        self._graph_sent: dict[str, Any] | None = None
        self._uses_time = bool(self._access.registry.publishers(_CLOCK))
        self._sim_ns = 0
        self._tasks: set[asyncio.Task[Any]] = set()
        self._ops = JsonOps("Foxglove", {
            "subscribe": (Subscribe, self._subscribe),
            "unsubscribe": (Unsubscribe, self._unsubscribe),
            "advertise": (Advertise, self._advertise),
            "unadvertise": (Unadvertise, self._unadvertise),
            "getParameters": (GetParameters, self._parameters.get),
            "setParameters": (SetParameters, self._parameters.set),
            "subscribeParameterUpdates": (ParameterUpdates, self._parameters.subscribe),
            "unsubscribeParameterUpdates": (ParameterUpdates, self._parameters.unsubscribe),
            "subscribeConnectionGraph": (ConnectionGraph, self._subscribe_graph),
            "unsubscribeConnectionGraph": (ConnectionGraph, self._unsubscribe_graph),
        })  # fmt: skip

    # -- the connection ---------------------------------------------------------------------------

    async def run(self, websocket: WebSocket) -> None:
        capabilities = _CAPABILITIES + (["time"] if self._uses_time else [])
        await self._send({
            "op": "serverInfo",
            "name": "Skydeck",
            "capabilities": capabilities,
            "supportedEncodings": ["json"],
            "metadata": {"ROS_DISTRO": ROS_DISTRO, "skydeck_core": self._access.core.participant.url},
            "sessionId": self._shared.session_id,
        })  # fmt: skip
        self._shared.graph.update()
        await self.follow_graph()
        if self._uses_time:
            self._follow(_CLOCK)
        limit = self._access.settings.max_message_bytes
        async for frame in incoming(websocket, limit):
            try:
                if frame is None:
                    raise Refused(f"a message of over {limit} bytes is refused (SKYDECK_MAX_MESSAGE_BYTES)")
                if isinstance(frame, bytes):
                    self._binary(frame)
                else:
                    await self._ops.dispatch(self._ops.parse(frame))
            except SkydeckError as error:  # Refused, and the core's own refusals
                await self._status(str(error))

    def close(self) -> None:
        for task in self._tasks:
            task.cancel()
        self._session.close()

    def spawn(self, coroutine: Coroutine[Any, Any, None]) -> None:
        task = asyncio.get_running_loop().create_task(coroutine)
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    async def _send(self, message: dict[str, Any]) -> None:
        await self._session.send_text(json.dumps(message))

    async def _status(self, text: str) -> None:
        await self._send({"op": "status", "level": ERROR, "message": text})

    def _binary(self, data: bytes) -> None:
        if not data:
            raise Refused("an empty binary message has no opcode")
        if data[0] == CLIENT_MESSAGE and len(data) >= 5:
            (cid,) = struct.unpack_from("<I", data, 1)
            self._publish(cid, data[5:])
        elif data[0] == SERVICE_REQUEST and len(data) >= 13:
            service, call, length = struct.unpack_from("<III", data, 1)
            encoding = data[13 : 13 + length].decode(errors="replace")
            self._call(service, call, encoding, data[13 + length :])
        else:
            raise Refused(f"binary opcode {data[0]:#04x} is not a client message (0x01) or service call (0x02)")

    # -- channels ---------------------------------------------------------------------------------

    async def follow_graph(self) -> None:
        """Advertise what appeared since the last call and unadvertise what went away."""
        graph = self._shared.graph
        # The state changes before the first await: a call running meanwhile sees it.
        visitor = self._session.visitor  # a client is not shown what its token may never use
        removed = [cid for cid in self._channels if cid not in graph.channels]
        added = [cid for cid in graph.channels if cid not in self._channels and _shown(visitor, Verb.READ, graph.channels[cid][0])]
        for cid in removed:
            topic, _ = self._channels.pop(cid)
            if topic in self._subscribed_topics:
                self._drop_subscription(self._subscribed_topics[topic])
        self._channels.update({cid: graph.channels[cid] for cid in added})
        gone = [sid for sid in self._services if sid not in graph.services]
        new = [sid for sid in graph.services if sid not in self._services and _shown(visitor, *service_verb(graph.services[sid][0], b""))]
        for sid in gone:
            del self._services[sid]
        self._services.update({sid: graph.services[sid][:2] for sid in new})
        if removed:
            await self._send({"op": "unadvertise", "channelIds": removed})
        if added:
            await self._send({"op": "advertise", "channels": [channel(cid, *self._channels[cid]) for cid in added]})
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
            })  # fmt: skip
        if self._graph_subscribed:
            await self._send_graph()

    def _subscribe(self, op: Subscribe) -> None:
        for item in op.subscriptions:
            if item.id in self._subscriptions:
                raise Refused(f"subscription id {item.id} is in use: unsubscribe it first")
            if item.channelId not in self._channels:
                raise Refused(f"no channel {item.channelId}: subscribe to a channel the server advertised")
            topic = self._channels[item.channelId][0]
            self._session.visitor.check(Verb.READ, topic)  # before anything of the op is kept
            if topic in self._subscribed_topics:
                raise Refused(
                    f"channel {item.channelId} ({topic}) is subscribed already (subscription {self._subscribed_topics[topic]})"
                )
            self._subscriptions[item.id] = self._channels[item.channelId]
            self._subscribed_topics[topic] = item.id
            self._follow(topic)

    def _unsubscribe(self, op: Unsubscribe) -> None:
        unknown = [sub_id for sub_id in op.subscriptionIds if sub_id not in self._subscriptions]
        for sub_id in op.subscriptionIds:
            if sub_id in self._subscriptions:
                self._drop_subscription(sub_id)
        if unknown:
            raise Refused(f"no subscription {unknown}")

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
            or (topic == PARAMETER_EVENTS and self._parameters.wanted)
        )
        reading = self._session.readings.get(topic)
        if not wanted:
            self._session.stop_reading(topic)
        elif reading is None:  # fenced when the client subscribes; the time and parameters are ours
            self._session.start_reading(
                topic, queue=DEFAULT_QUEUE, encode=self._encoder(topic), for_client=topic in self._subscribed_topics
            )

    def _encoder(self, topic: str) -> Callable[[str], Sequence[dict[str, Any]]]:
        payloads = self._shared.payloads

        def encode(frame: str) -> Sequence[dict[str, Any]]:
            messages: list[dict[str, Any]] = []
            if topic == _CLOCK and self._uses_time:
                self._sim_ns = _clock_ns(frame, self._sim_ns)
                messages.append({"type": "websocket.send", "bytes": struct.pack("<BQ", TIME, self._sim_ns)})
            if topic == PARAMETER_EVENTS:
                messages += self._parameters.updates(frame)
            sub_id = self._subscribed_topics.get(topic)
            if sub_id is not None:
                _, msg_type = self._subscriptions[sub_id]
                now = self._sim_ns if self._uses_time else time.time_ns()
                data = struct.pack("<BIQ", MESSAGE_DATA, sub_id, now) + payloads.payload(topic, msg_type, frame)
                messages.append({"type": "websocket.send", "bytes": data})
            return messages

        return encode

    # -- client publishing ------------------------------------------------------------------------

    def _advertise(self, op: Advertise) -> None:
        for item in op.channels:
            if item.encoding != "json":
                raise Refused(f"channel {item.id}: encoding {item.encoding!r} is not supported: use json")
            try:
                topic = resolve_name(item.topic)
            except InvalidNameError as error:
                raise Refused(f"channel {item.id}: {error}") from None
            try:
                self._session.declare(topic, declared_type(item.schemaName))
            except (FrameRejected, AccessRefused) as error:
                raise Refused(f"channel {item.id} ({topic}): {error}") from None
            self._client_channels[item.id] = topic

    def _unadvertise(self, op: Unadvertise) -> None:
        for cid in op.channelIds:
            topic = self._client_channels.pop(cid, None)
            if topic is not None and topic not in self._client_channels.values():
                self._session.stop_publishing(topic)

    def _publish(self, cid: int, payload: bytes) -> None:
        topic = self._client_channels.get(cid)
        if topic is None:
            raise Refused(f"no client channel {cid}: advertise it first")
        try:
            text = publishable_text(payload)
        except ValueError as error:
            raise Refused(f"channel {cid} ({topic}): the payload is not JSON text: {error}") from None
        try:
            self._session.publish(topic, text)
        except (FrameRejected, AccessRefused) as error:
            raise Refused(f"channel {cid} ({topic}): {error}") from None

    # -- services ---------------------------------------------------------------------------------

    def _call(self, service_id: int, call_id: int, encoding: str, payload: bytes) -> None:
        if service_id not in self._services:
            raise Refused(f"no service {service_id}: call a service the server advertised")
        if len(self._tasks) >= _MAX_CALLS_IN_FLIGHT:
            raise Refused(f"{_MAX_CALLS_IN_FLIGHT} calls are already in flight on this connection")
        self.spawn(self._answer(service_id, call_id, encoding, payload))

    async def _answer(self, service_id: int, call_id: int, encoding: str, payload: bytes) -> None:
        name = self._services[service_id][0]
        try:
            if encoding != "json":
                raise Refused(f"encoding {encoding!r} is not supported: use json")
            reply = await self._session.call(name, payload)
            if not reply.answered:
                raise Refused(reply.detail())
        except (Refused, ServiceCallFailed) as error:
            await self._send({"op": "serviceCallFailure", "serviceId": service_id, "callId": call_id, "message": str(error)})
            return
        header = struct.pack("<BIII", SERVICE_RESPONSE, service_id, call_id, 4) + b"json"
        await self._session.send_bytes(header + reply.body)

    # -- the connection graph ---------------------------------------------------------------------

    async def _subscribe_graph(self, op: ConnectionGraph) -> None:
        self._graph_subscribed = True
        self._graph_sent = None
        await self._send_graph()

    def _unsubscribe_graph(self, op: ConnectionGraph) -> None:
        self._graph_subscribed = False

    async def _send_graph(self) -> None:
        update = self._shared.graph.connection_graph(self._graph_sent)
        self._graph_sent = self._shared.graph.graph_state()
        if update is not None:
            await self._send(update)


def _shown(visitor: Pass, verb: Verb, name: str) -> bool:
    """Whether a client is shown a channel or service: unless its token may never use it (a
    student's, outside their fences); without a token, it is shown (a token would open it), and
    so is a service whose fence depends on the request (the node a kill_node names: ``name`` "")."""
    return not name or not isinstance(visitor.refusal(verb, name), Forbidden)


def _clock_ns(frame: str, previous: int) -> int:
    """The time a ``/clock`` frame says (a builtin_interfaces Time, or a rosgraph_msgs Clock)."""
    try:
        value = json.loads(frame)
        return Time.model_validate(value.get("clock", value)).to_nsec()
    except (ValueError, AttributeError):
        return previous
