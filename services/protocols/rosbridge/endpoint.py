"""rosbridge v2: roslibjs and roslibpy clients on the core's one topic edge and call path.

    ws://CORE:9090/          (``--rosbridge-port``; 0 turns it off)
    ws://CORE:8000/rosbridge (always, on the core's own port)

Each JSON text frame is one op (:mod:`.ops` reads them), carried out as rosbridge_suite's
protocol document has it: topics by :mod:`.topics` (through the connection's
:class:`~services.protocols.session.ClientSession`: an outbox per topic, the edge's validation
and token), services by :mod:`.service_ops` (the HTTP gateway's call path), ROS 2's action ops
by :mod:`.actions` (goals a client sends) and :mod:`.action_hosting` (an action a client serves);
ROS 1's actionlib is topics.

Unlike a native socket, a rosbridge connection gets back what it publishes on a topic it
reads, as ROS delivers a node's own messages to its subscriptions (rosbridge_suite's
subscriptions are such a node's): one roslibpy script may publish and listen on one topic.

A bad frame gets a ``status`` (level ``error``, the op's ``id``) and nothing else happens;
``set_level`` asks for ``warning`` and ``info`` statuses too, or ``none``. Statuses are replies
to a client's own ops, never sent otherwise. A client that stops reading is closed with 4001
(see :mod:`services.protocols.session`). ``auth`` (:mod:`.auth`) makes the connection act as a
token's subject: the process token (or rosauth's MAC made with it), or a class token.

Every op is fenced for the connection's token (:mod:`services.access`): ``subscribe``,
``advertise``, ``publish``, ``advertise_service`` and ``advertise_action`` refused get a
``status`` error, a refused ``call_service`` its ``service_response`` with ``result: false``, a
refused ``send_action_goal`` its ``action_result``; a student's connection that publishes over
their rate is closed with 4002.
"""

from __future__ import annotations

import logging
from typing import Any

from starlette.websockets import WebSocket

import services.protocols.rosbridge.clock as clock
from services.core.access import CoreAccess
from services.protocols.ops import JsonOps, Refused
from services.protocols.rosbridge.action_hosting import (
    ActionFeedback,
    ActionResult,
    AdvertiseAction,
    HostedActions,
    UnadvertiseAction,
)
from services.protocols.rosbridge.actions import ActionGoals, CancelActionGoal, SendActionGoal
from services.protocols.rosbridge.auth import authenticates
from services.protocols.rosbridge.frames import PublishEnvelopes, Replies, status_frame
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
)
from services.protocols.rosbridge.service_ops import ConnectionServices
from services.protocols.rosbridge.tf_republisher import TFRepublisher
from services.protocols.rosbridge.topics import ConnectionTopics
from services.protocols.session import ClientSession, incoming
from services.runtime.edge.frames import close_with
from shared_models import Message, UnknownInterfaceError, get_interface
from shared_models.errors import SkydeckError

__all__ = ["RosbridgeEndpoint"]

logger = logging.getLogger("skydeck.rosbridge")

_LEVELS = ("info", "warning", "error", "none")


class RosbridgeEndpoint:
    """Serves rosbridge connections; the publish envelope of each frame is made once for all."""

    def __init__(self, access: CoreAccess, tf_republisher: TFRepublisher | None = None) -> None:
        self.access = access
        self._tf_republisher = tf_republisher  # the core's guest, closed with the endpoint
        self.envelopes = PublishEnvelopes(self._message_type, self._receive_time)

    async def serve(self, websocket: WebSocket) -> None:
        """One rosbridge connection, from handshake to close."""
        await websocket.accept()
        session = ClientSession.open(self.access, websocket, "rosbridge", echo=True)
        connection = _Connection(self, session)
        try:
            stalled = await session.serve(connection.run(websocket), advice="subscribe with a throttle_rate")
        finally:
            connection.close()
        if stalled is not None:
            await close_with(websocket, stalled.code, stalled.reason)

    def close(self) -> None:
        """The core stops: tf2_web_republisher's watches end (each connection closes its own)."""
        if self._tf_republisher is not None:
            self._tf_republisher.close()

    def _message_type(self, topic: str) -> type[Message] | None:
        known = self.access.registry.topic_type(topic)
        if not known:
            return None
        try:
            found = get_interface(known)
        except UnknownInterfaceError:
            return None
        return found if isinstance(found, type) and issubclass(found, Message) else None

    def _receive_time(self) -> tuple[int, int]:
        stamp = clock.now(self.access)
        return stamp.sec, stamp.nanosec


class _Connection:
    """One client: its ops, status level and fragments; topics, services and actions by their modules."""

    def __init__(self, endpoint: RosbridgeEndpoint, session: ClientSession) -> None:
        self._session = session
        self._settings = endpoint.access.settings
        self._level = _LEVELS.index("error")
        self._fragments = FragmentBuffer(self._settings.max_message_bytes)
        replies = Replies()
        topics = ConnectionTopics(session, endpoint.envelopes, self._status, self._wants)
        self._services = services = ConnectionServices(session, replies, self._status)
        self._goals = goals = ActionGoals(session, replies)  # ROS 2's actions the client sends goals to
        self._hosted = hosted = HostedActions(session, self._status)  # ROS 2's actions the client serves
        self._ops = JsonOps("rosbridge", {
            "advertise": (Advertise, topics.advertise),
            "unadvertise": (Unadvertise, topics.unadvertise),
            "publish": (Publish, topics.publish),
            "subscribe": (Subscribe, topics.subscribe),
            "unsubscribe": (Unsubscribe, topics.unsubscribe),
            "call_service": (CallService, services.call_service),
            "service_response": (ServiceResponse, services.service_response),
            "advertise_service": (AdvertiseService, services.advertise_service),
            "unadvertise_service": (UnadvertiseService, services.unadvertise_service),
            "send_action_goal": (SendActionGoal, goals.send_goal),
            "cancel_action_goal": (CancelActionGoal, goals.cancel_goal),
            "advertise_action": (AdvertiseAction, hosted.advertise),
            "unadvertise_action": (UnadvertiseAction, hosted.unadvertise),
            "action_feedback": (ActionFeedback, hosted.feedback),
            "action_result": (ActionResult, hosted.result),
            "set_level": (SetLevel, self._set_level),
            "auth": (Auth, self._auth),
            "fragment": (Fragment, self._fragment),
        })  # fmt: skip

    # -- the connection ---------------------------------------------------------------------------

    async def run(self, websocket: WebSocket) -> None:
        limit = self._settings.max_message_bytes
        async for frame in incoming(websocket, limit):
            if frame is None:
                await self._status("error", f"a frame of over {limit} bytes is refused (SKYDECK_MAX_MESSAGE_BYTES)")
            elif isinstance(frame, bytes):
                await self._status("error", "rosbridge frames from a client are JSON text: binary (CBOR, BSON) is not read here")
            else:
                await self._handle(frame)

    def close(self) -> None:
        self._services.close()
        self._goals.close()
        self._hosted.close()
        self._session.close()

    async def _handle(self, text: str) -> None:
        op_id = None
        try:
            frame = self._ops.parse(text)
            op_id = frame.get("id")
            await self._ops.dispatch(frame)
        except SkydeckError as error:  # Refused, and the core's own refusals
            await self._status("error", str(error), op_id)

    def _wants(self, level: str) -> bool:
        return _LEVELS.index(level) >= self._level and level != "none"

    async def _status(self, level: str, text: str, op_id: Any = None) -> None:
        """A status reply, if the client's level asks for this one (``set_level``)."""
        if self._wants(level):
            await self._session.send_text(status_frame(level, text, op_id))

    # -- the connection's own ops -----------------------------------------------------------------

    async def _set_level(self, op: SetLevel) -> None:
        if op.level not in _LEVELS:
            raise Refused(f"level must be one of {', '.join(_LEVELS)}, got {op.level!r}")
        self._level = _LEVELS.index(op.level)

    async def _auth(self, op: Auth) -> None:
        process = self._settings.token
        # rosauth's MAC proves the process token; anything else is taken as a token itself (the
        # process token, or a class token), and refused if nobody has it.
        token = process if process and authenticates(op, process) else op.mac
        self._session.authenticate(token)
        await self._status("info", f"authenticated as {self._session.visitor.subject}", op.id)

    async def _fragment(self, op: Fragment) -> None:
        whole = self._fragments.add(op)
        if whole is not None:
            await self._handle(whole)
