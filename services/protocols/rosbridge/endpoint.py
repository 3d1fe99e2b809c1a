"""rosbridge v2: roslibjs and roslibpy clients on the core's one topic edge and call path.

    ws://CORE:9090/          (``--rosbridge-port``; 0 turns it off)
    ws://CORE:8000/rosbridge (always, on the core's own port)

Each JSON text frame is one op (:mod:`.ops` reads them). Topics are read and published
through the connection's :class:`~services.protocols.session.ClientSession` (an outbox per
topic, the edge's validation, token and "no echo"); ``call_service`` takes the HTTP gateway's
call path, and always ends with a ``service_response``: ``result: false`` and the reason in
``values`` when it failed (no service, no answer within its ``timeout`` or the gateway's, no
token), and nothing else, as rosbridge_server answers. A service a client advertises is hosted
by the core for it, so nodes and ``curl`` call it like any other. ROS 2's action ops
(``send_action_goal``, ``cancel_action_goal``) are :mod:`.actions`'; ROS 1's actionlib is topics.

A bad frame gets a ``status`` (level ``error``, the op's ``id``) and nothing else happens;
``set_level`` asks for ``warning`` and ``info`` statuses too, or ``none``. Statuses are replies
to a client's own ops, never sent otherwise. A client that stops reading is closed with 4001
(see :mod:`services.protocols.session`). ``auth`` with a token as ``mac`` (the process token, or
a class token) makes the connection act as that token's subject.

Every op is fenced for the connection's token (:mod:`services.access`): ``subscribe``,
``advertise``, ``publish`` and ``advertise_service`` refused get a ``status`` error, a refused
``call_service`` its ``service_response`` with ``result: false``; a student's connection that
publishes over their rate is closed with 4002.
"""

from __future__ import annotations

import asyncio
import itertools
import json
import logging
from dataclasses import dataclass
from typing import Any

from pydantic import ValidationError
from starlette.websockets import WebSocket

from services.access import Verb
from services.core.access import CoreAccess
from services.core.gateway_topic import declared_type
from services.protocols.ops import JsonOps, Refused, describe_error
from services.protocols.rosbridge.actions import ActionGoals, CancelActionGoal, SendActionGoal
from services.protocols.rosbridge.frames import PublishEnvelopes, fragments, status_frame
from services.protocols.rosbridge.ops import (
    Advertise,
    AdvertiseService,
    Auth,
    CallService,
    Fragment,
    FragmentBuffer,
    Publish,
    ServiceResponse,
    SetLevel,
    Subscribe,
    Unadvertise,
    UnadvertiseService,
    Unsubscribe,
    request_body,
    ros2_time_names,
)
from services.protocols.session import ClientSession, incoming
from services.runtime.edge.frames import FrameRejected, close_with
from services.runtime.edge.pump import Encode
from services.runtime.errors import ServiceUnavailableError
from services.runtime.service import ServiceHandlerError
from services.runtime.wire import DEFAULT_QUEUE
from shared_models import Message, ServiceType, get_interface, resolve_name
from shared_models.errors import SkydeckError

__all__ = ["RosbridgeEndpoint"]

logger = logging.getLogger("skydeck.rosbridge")

_LEVELS = ("info", "warning", "error", "none")
_MAX_CALLS_IN_FLIGHT = 256


class RosbridgeEndpoint:
    """Serves rosbridge connections; the publish envelope of each frame is made once for all."""

    def __init__(self, access: CoreAccess) -> None:
        self.access = access
        self.envelopes = PublishEnvelopes()

    async def serve(self, websocket: WebSocket) -> None:
        """One rosbridge connection, from handshake to close."""
        await websocket.accept()
        session = ClientSession.open(self.access, websocket, "rosbridge")
        connection = _Connection(self, session)
        try:
            stalled = await session.serve(connection.run(websocket), advice="subscribe with a throttle_rate")
        finally:
            connection.close()
        if stalled is not None:
            await close_with(websocket, stalled.code, stalled.reason)

    def close(self) -> None:
        """Nothing outlives the connections (each closes its own when it ends)."""


@dataclass
class _Subscription:
    """One subscribe op's options (a client may subscribe to one topic several times)."""

    throttle_ms: int
    queue_length: int
    fragment_size: int | None


class _Connection:
    """One client: its subscriptions, advertisements, hosted services and calls in flight."""

    def __init__(self, endpoint: RosbridgeEndpoint, session: ClientSession) -> None:
        self._endpoint = endpoint
        self._session = session
        self._settings = endpoint.access.settings
        self._level = _LEVELS.index("error")
        self._subscriptions: dict[str, dict[Any, _Subscription]] = {}
        self._reading: dict[str, tuple[int, int, int | None]] = {}  # topic -> merged options
        self._hosted: dict[str, _ClientService] = {}
        self._calls: set[asyncio.Task[None]] = set()
        self._fragments = FragmentBuffer(self._settings.max_message_bytes)
        self._actions = ActionGoals(session)  # ROS 2's action ops (.actions)
        self._ops = JsonOps("rosbridge", {
            "advertise": (Advertise, self._advertise),
            "unadvertise": (Unadvertise, self._unadvertise),
            "publish": (Publish, self._publish),
            "subscribe": (Subscribe, self._subscribe),
            "unsubscribe": (Unsubscribe, self._unsubscribe),
            "call_service": (CallService, self._call_service),
            "service_response": (ServiceResponse, self._service_response),
            "advertise_service": (AdvertiseService, self._advertise_service),
            "unadvertise_service": (UnadvertiseService, self._unadvertise_service),
            "set_level": (SetLevel, self._set_level),
            "auth": (Auth, self._auth),
            "fragment": (Fragment, self._fragment),
            "send_action_goal": (SendActionGoal, self._actions.send_goal),
            "cancel_action_goal": (CancelActionGoal, self._actions.cancel_goal),
        })  # fmt: skip

    # -- the connection ---------------------------------------------------------------------------

    async def run(self, websocket: WebSocket) -> None:
        limit = self._settings.max_message_bytes
        async for frame in incoming(websocket, limit):
            if frame is None:
                await self._status("error", f"a frame of over {limit} bytes is refused (SKYDECK_MAX_MESSAGE_BYTES)")
            elif isinstance(frame, bytes):
                await self._status("error", "rosbridge frames are JSON text: binary (CBOR, BSON) is not supported here")
            else:
                await self._handle(frame)

    def close(self) -> None:
        for task in self._calls:
            task.cancel()
        for service in self._hosted.values():
            service.fail_pending(f"the rosbridge client hosting {service.name} disconnected")
        self._actions.close()
        self._session.close()

    async def _handle(self, text: str) -> None:
        op_id = None
        try:
            frame = self._ops.parse(text)
            op_id = frame.get("id")
            await self._ops.dispatch(frame)
        except SkydeckError as error:  # Refused, and the core's own refusals
            await self._status("error", str(error), op_id)

    async def _status(self, level: str, text: str, op_id: Any = None) -> None:
        """A status reply, if the client's level asks for this one (``set_level``)."""
        if _LEVELS.index(level) >= self._level and level != "none":
            await self._session.send_text(status_frame(level, text, op_id))

    # -- topics ---------------------------------------------------------------------------------

    async def _advertise(self, op: Advertise) -> None:
        name = resolve_name(op.topic)
        self._session.declare(name, declared_type(op.type))
        await self._status("info", f"advertised {name} ({op.type})", op.id)

    async def _unadvertise(self, op: Unadvertise) -> None:
        name = resolve_name(op.topic)
        if not self._session.stop_publishing(name):
            await self._status("warning", f"{name} was not advertised by this client", op.id)

    async def _publish(self, op: Publish) -> None:
        name = resolve_name(op.topic)
        try:
            self._session.publish(name, ros2_time_names(json.dumps(op.msg), op.msg))
        except FrameRejected as error:
            raise Refused(f"publish to {name}: {error.reason}") from None

    async def _subscribe(self, op: Subscribe) -> None:
        name = resolve_name(op.topic)
        self._session.visitor.check(Verb.READ, name)  # before anything of the op is kept
        if op.type:
            declared = declared_type(op.type)
            known = self._endpoint.access.registry.topic_type(name)
            if declared is not None and known and known != declared.__ros_type__:
                raise Refused(f"{name} is {known}, not {op.type}")
        if op.compression not in (None, "none"):
            raise Refused(f"compression {op.compression!r} is not supported: leave it out or use 'none'")
        self._subscriptions.setdefault(name, {})[op.id] = _Subscription(
            op.throttle_rate, op.queue_length, op.fragment_size
        )
        self._follow(name)
        await self._status("info", f"subscribed to {name}", op.id)

    async def _unsubscribe(self, op: Unsubscribe) -> None:
        name = resolve_name(op.topic)
        subscriptions = self._subscriptions.get(name)
        if not subscriptions or (op.id is not None and op.id not in subscriptions):
            await self._status("warning", f"no subscription to {name} with id {op.id!r}", op.id)
            return
        if op.id is None:
            subscriptions.clear()
        else:
            del subscriptions[op.id]
        self._follow(name)

    def _follow(self, topic: str) -> None:
        """(Re)start or stop reading ``topic`` with the merged options of its subscriptions:
        the lowest throttle and fragment size, the longest queue (as rosbridge merges them)."""
        subscriptions = self._subscriptions.get(topic)
        if not subscriptions:
            self._subscriptions.pop(topic, None)
            self._reading.pop(topic, None)
            self._session.stop_reading(topic)
            return
        throttle = min(s.throttle_ms for s in subscriptions.values())
        queue = max(s.queue_length for s in subscriptions.values())
        sizes = [s.fragment_size for s in subscriptions.values() if s.fragment_size]
        merged = (throttle, queue, min(sizes) if sizes else None)
        if self._reading.get(topic) == merged:
            return
        self._reading[topic] = merged
        encode: Encode = self._endpoint.envelopes.encoder(topic)
        if merged[2] is not None:
            encode = fragments(encode, merged[2], topic)
        # As rosbridge_server: throttled without a queue_length, the newest message each period;
        # with one, every message that queue holds, one per period, oldest first.
        self._session.start_reading(
            topic,
            queue=queue or DEFAULT_QUEUE,
            rate_hz=1000.0 / throttle if throttle > 0 else None,
            paced_queue=throttle > 0 and queue > 1,
            encode=encode,
        )

    # -- services: calling ----------------------------------------------------------------------

    async def _call_service(self, op: CallService) -> None:
        if len(self._calls) >= _MAX_CALLS_IN_FLIGHT:
            raise Refused(f"{_MAX_CALLS_IN_FLIGHT} service calls are already in flight on this connection")
        task = asyncio.get_running_loop().create_task(self._answer_call(op))
        self._calls.add(task)
        task.add_done_callback(self._calls.discard)

    async def _answer_call(self, op: CallService) -> None:
        values: Any
        try:
            name = resolve_name(op.service)
            body = request_body(op.args, self._request_type(name, op.type))
            reply = await self._session.call(name, body, timeout_s=op.timeout)
            if reply.answered:
                values, result = json.loads(reply.body), True
            else:
                values, result = reply.detail(), False
        except (SkydeckError, ValueError) as error:
            values, result, name = str(error), False, op.service
        # A failure is this response alone, as rosbridge_server sends it (it logs the error on its
        # side and sends no `status`, for which roslibpy has no handler: issue 32).
        response: dict[str, Any] = {"op": "service_response", "service": name, "values": values, "result": result}
        if op.id is not None:
            response["id"] = op.id
        text = json.dumps(response)
        if op.fragment_size and len(text) > op.fragment_size:
            for message in fragments(lambda frame: ({"type": "websocket.send", "text": frame},), op.fragment_size, name)(text):
                await self._session.send_text(message["text"])
        else:
            await self._session.send_text(text)

    def _request_type(self, name: str, given: str | None) -> type[Message] | None:
        """The request type of service ``name`` (to read positional ``args``), if known."""
        type_name = given
        found = self._endpoint.access.registry.service(name)
        if found is not None:
            type_name = found[0].type
        if not type_name:
            return None
        try:
            srv = get_interface(type_name)
        except SkydeckError:
            return None
        return srv.Request if isinstance(srv, type) and issubclass(srv, ServiceType) else None

    # -- services: hosting ----------------------------------------------------------------------

    async def _advertise_service(self, op: AdvertiseService) -> None:
        name = resolve_name(op.service)
        self._session.visitor.check(Verb.SERVE, name)
        srv = get_interface(op.type)
        if not (isinstance(srv, type) and issubclass(srv, ServiceType)):
            raise Refused(f"{op.type} is a message type, not a service type")
        found = self._endpoint.access.registry.service(name)
        if found is not None and name not in self._hosted:
            raise Refused(f"{name} is already served by {found[1].description.name}")
        service = self._hosted.get(name)
        if service is not None:
            service.fail_pending(f"{name} was advertised again")
        self._hosted[name] = service = _ClientService(name, srv, self._session)
        self._session.guest.serves(service)
        await self._status("info", f"serving {name} ({op.type})", op.id)

    async def _unadvertise_service(self, op: UnadvertiseService) -> None:
        name = resolve_name(op.service)
        service = self._hosted.pop(name, None)
        if service is None:
            await self._status("warning", f"{name} is not served by this client", op.id)
            return
        service.fail_pending(f"{name} was unadvertised")
        self._session.guest.stops_serving(name)

    async def _service_response(self, op: ServiceResponse) -> None:
        name = resolve_name(op.service)
        service = self._hosted.get(name)
        if service is None or not service.answer(op):
            raise Refused(f"no call {op.id!r} to {name} is waiting for an answer")

    # -- the connection's own ops -----------------------------------------------------------------

    async def _set_level(self, op: SetLevel) -> None:
        if op.level not in _LEVELS:
            raise Refused(f"level must be one of {', '.join(_LEVELS)}, got {op.level!r}")
        self._level = _LEVELS.index(op.level)

    async def _auth(self, op: Auth) -> None:
        self._session.authenticate(op.mac)
        await self._status("info", f"authenticated as {self._session.visitor.subject}", op.id)

    async def _fragment(self, op: Fragment) -> None:
        whole = self._fragments.add(op)
        if whole is not None:
            await self._handle(whole)


class _ClientService:
    """A service a rosbridge client hosts: the core forwards each call to it as ``call_service``
    and waits for its ``service_response`` (the caller's timeout applies: 504 if none comes)."""

    def __init__(self, name: str, srv_type: type[ServiceType], session: ClientSession) -> None:
        self.name = name
        self.srv_type = srv_type
        self._session = session
        self._ids = itertools.count(1)
        self._pending: dict[str, asyncio.Future[ServiceResponse]] = {}

    async def handle(self, request: Message, logger: logging.Logger) -> Message:
        call_id = f"service_request:{self.name}:{next(self._ids)}"
        future: asyncio.Future[ServiceResponse] = asyncio.get_running_loop().create_future()
        self._pending[call_id] = future
        try:
            await self._session.send_text(json.dumps({
                "op": "call_service",
                "id": call_id,
                "service": self.name,
                "args": request.model_dump(mode="json"),
            }))
            answer = await future
        finally:
            self._pending.pop(call_id, None)
        if not answer.result:
            raise ServiceHandlerError(f"the rosbridge client serving {self.name} failed: {answer.values}")
        try:
            return self.srv_type.Response.model_validate(answer.values if answer.values is not None else {})
        except ValidationError as error:
            raise ServiceHandlerError(
                f"the rosbridge client serving {self.name} answered {describe_error('service_response', error)}"
            ) from None

    def answer(self, op: ServiceResponse) -> bool:
        future = self._pending.get(str(op.id))
        if future is None or future.done():
            return False
        future.set_result(op)
        return True

    def fail_pending(self, reason: str) -> None:
        for future in self._pending.values():
            if not future.done():
                future.set_exception(ServiceUnavailableError(self.name, reason))

