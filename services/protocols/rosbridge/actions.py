"""rosbridge's ROS 2 action ops: a client sends goals through the core, which is their action client.

    {"op": "send_action_goal", "id": "g1", "action": "/fibonacci",
     "action_type": "example_interfaces/action/Fibonacci", "args": {"order": 5}, "feedback": true}
    <- {"op": "action_feedback", "id": "g1", "action": "/fibonacci", "values": {"sequence": [0, 1, 1]}}
    <- {"op": "action_result", "id": "g1", "action": "/fibonacci", "values": {"sequence": [...]},
        "status": 4, "result": true}
    {"op": "cancel_action_goal", "id": "g1", "action": "/fibonacci"}

As rosbridge_server does it: the goal goes to the server once one is there (waiting up to
``SERVER_WAIT_S``), ``action_feedback`` carries the Feedback part of each feedback (when the op
asked for it), and ``action_result`` the Result with the goal's final ``action_msgs/GoalStatus``
and ``result: true``, whether the goal succeeded, was cancelled or aborted; a goal that could not
be run (no server, refused, a type or args that do not fit, no token) ends with ``result:
false``, the reason in ``values`` and status 0. ``cancel_action_goal`` names the goal by the
``id`` its ``send_action_goal`` had; its result comes as for any goal.

The core reaches the graph for these goals as it does for everything else: calls take the
gateway's one call path with the connection's token, feedback and status are taps on the core
node (:class:`CoreTransport`), and the client shows in the graph as reading them.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Sequence
from typing import Any

from pydantic import Field, ValidationError

from services.access import Verb
from services.core.service_calls import ServiceCallFailed
from services.protocols.ops import Refused
from services.protocols.rosbridge.frames import Replies
from services.protocols.rosbridge.ops import RosbridgeOp
from services.protocols.session import ClientSession
from services.runtime.actions.client import ActionClient, ClientGoal
from services.runtime.actions.goals import GoalStatusCode
from services.runtime.errors import ServiceCallRejectedError, ServiceTimeoutError
from services.runtime.subscription import RawSubscription
from shared_models import ActionType, Message, ServiceType, get_interface, resolve_name
from shared_models.errors import SkydeckError

__all__ = ["SERVER_WAIT_S", "ActionGoals", "CancelActionGoal", "CoreTransport", "SendActionGoal"]

SERVER_WAIT_S = 2.0  # rosbridge_server waits 1 s; a loaded machine links a little slower
_TAP_DEPTH = 100
_MAX_GOALS_IN_FLIGHT = 256


class SendActionGoal(RosbridgeOp):
    action: str
    action_type: str
    args: dict[str, Any] | list[Any] | None = None
    feedback: bool = False
    fragment_size: int | None = Field(default=None, gt=0)
    compression: str | None = None


class CancelActionGoal(RosbridgeOp):
    id: str | int
    action: str


class _GoalFailed(SkydeckError):
    """A goal that could not be run: its ``action_result`` has ``result: false`` and this text."""


class CoreTransport:
    """An action client's way into the graph from one rosbridge connection of the core."""

    def __init__(self, session: ClientSession) -> None:
        self._session = session
        self._taps: list[tuple[str, RawSubscription]] = []

    async def call(self, service: str, srv_type: type[ServiceType], request: Message, timeout_s: float) -> Any:
        try:
            reply = await self._session.call(service, request.model_dump_json().encode(), timeout_s=timeout_s)
        except ServiceCallFailed as failed:
            if failed.status == 504:
                raise ServiceTimeoutError(service, str(failed)) from None
            raise
        if not reply.answered:
            raise ServiceCallRejectedError(service, reply.detail(), reply.status)
        return srv_type.Response.model_validate_json(reply.body)

    def subscribe(self, topic: str, msg_type: type[Message], callback: Callable[[Any], None]) -> None:
        # Fenced as any reading (a class's student: their own actions' feedback and status only);
        # refused, the goal's action_result says why.
        self._session.visitor.check(Verb.READ, topic)
        tap = RawSubscription(topic, msg_type, lambda frame: callback(msg_type.model_validate_json(frame)), _TAP_DEPTH)
        self._session.access.core.start_reading(topic, tap)
        self._session.guest.reads(topic, msg_type.__ros_type__)
        self._taps.append((topic, tap))

    async def served(self, services: Sequence[tuple[str, type[ServiceType]]]) -> bool:
        registry = self._session.access.registry
        return all(registry.service(name) is not None for name, _ in services)

    def linked(self, topic: str) -> bool:
        return self._session.access.core.participant.is_linked(topic)

    def close(self) -> None:
        for topic, tap in self._taps:
            self._session.access.core.stop_reading(topic, tap)
            self._session.guest.stops_reading(topic)
        self._taps.clear()


class _Goal:
    """One send_action_goal in flight: its task, and its goal once the server has answered."""

    def __init__(self, op: SendActionGoal) -> None:
        self.op = op
        self.task: asyncio.Task[None] | None = None
        self.client: ActionClient | None = None
        self.sent: ClientGoal | None = None
        self.cancel_asked = False
        self.sending: asyncio.Future[None] | None = None  # the latest message on its way, in order


class ActionGoals:
    """One connection's goals (see the module docstring)."""

    def __init__(self, session: ClientSession, replies: Replies) -> None:
        self._session = session
        self._replies = replies
        self._clients: dict[tuple[str, str], ActionClient] = {}  # one per action (and type)
        self._goals: dict[str | int | None, _Goal] = {}

    async def send_goal(self, op: SendActionGoal) -> None:
        try:
            Replies.check(op.compression)
        except ValueError as error:
            raise Refused(f"send_action_goal: {error}") from None
        if op.id is not None and op.id in self._goals:
            raise Refused(f"a goal with id {op.id!r} is in flight on this connection: give each goal its own id")
        if len(self._goals) >= _MAX_GOALS_IN_FLIGHT:
            raise Refused(f"{_MAX_GOALS_IN_FLIGHT} action goals are already in flight on this connection")
        goal = _Goal(op)
        self._goals[op.id] = goal
        goal.task = asyncio.get_running_loop().create_task(self._run(goal))
        goal.task.add_done_callback(lambda _: self._forget(goal))

    async def cancel_goal(self, op: CancelActionGoal) -> None:
        goal = self._goals.get(op.id)
        if goal is None or resolve_name(goal.op.action) != resolve_name(op.action):
            raise Refused(f"cancel_action_goal: no goal with id {op.id!r} of {op.action} is in flight on this connection")
        goal.cancel_asked = True
        if goal.client is not None and goal.sent is not None and goal.sent.accepted:
            await goal.client.cancel(goal.sent)  # (else cancelled as soon as it is accepted)

    def _forget(self, goal: _Goal) -> None:
        if self._goals.get(goal.op.id) is goal:
            del self._goals[goal.op.id]

    def close(self) -> None:
        for goal in self._goals.values():
            if goal.task is not None:
                goal.task.cancel()
        for client in self._clients.values():
            client.close()
        self._clients.clear()

    # -- one goal -------------------------------------------------------------------------------

    async def _run(self, goal: _Goal) -> None:
        op = goal.op
        try:
            response = await self._result_of(goal)
        except (SkydeckError, ValueError) as error:  # _GoalFailed, and the core's own refusals
            result = {"op": "action_result", "action": op.action, "values": str(error).splitlines()[0],
                      "status": GoalStatusCode.UNKNOWN, "result": False}  # fmt: skip
        else:
            result = {"op": "action_result", "action": op.action, "values": response.result.model_dump(mode="json"),
                      "status": response.status, "result": True}  # fmt: skip
        self._queue(goal, result)
        if goal.sending is not None:
            await goal.sending

    async def _result_of(self, goal: _Goal) -> Any:
        op = goal.op
        name = resolve_name(op.action)
        action_type = get_interface(op.action_type)
        if not (isinstance(action_type, type) and issubclass(action_type, ActionType)):
            raise _GoalFailed(f"{op.action_type} is not an action type")
        try:
            request = action_type.Goal.model_validate(_fields(op.args, action_type.Goal))
        except ValidationError as error:
            first = error.errors(include_url=False)[0]
            where = ".".join(str(part) for part in first["loc"]) or "(goal)"
            raise _GoalFailed(f"args do not fit {action_type.Goal.__ros_type__}: {where}: {first['msg']}") from None
        client = goal.client = self._client(name, action_type)
        if not await client.wait_for_server(timeout_s=SERVER_WAIT_S):
            raise _GoalFailed("No action server available")
        on_feedback = None
        if op.feedback:
            def on_feedback(message: Any) -> None:
                values = message.feedback.model_dump(mode="json")
                self._queue(goal, {"op": "action_feedback", "action": op.action, "values": values})
        goal.sent = await client.send_goal(request, on_feedback=on_feedback)
        if not goal.sent.accepted:
            raise _GoalFailed("Action goal was rejected")
        if goal.cancel_asked:
            await client.cancel(goal.sent)
        return await client.get_result(goal.sent)

    def _client(self, name: str, action_type: type[ActionType]) -> ActionClient:
        key = (name, action_type.__ros_type__)
        client = self._clients.get(key)
        if client is None:
            client = self._clients[key] = ActionClient(CoreTransport(self._session), action_type, name)
        return client

    def _queue(self, goal: _Goal, message: dict[str, Any]) -> None:
        """Send ``message`` after the goal's earlier ones (feedback, then its result)."""
        previous = goal.sending

        async def in_turn() -> None:
            if previous is not None:
                await previous
            await self._send(goal, message)

        goal.sending = asyncio.ensure_future(in_turn())

    async def _send(self, goal: _Goal, message: dict[str, Any]) -> None:
        if goal.op.id is not None:
            message["id"] = goal.op.id
        op = goal.op
        for text in self._replies.texts(message, compression=op.compression, fragment_size=op.fragment_size, label=op.action):
            await self._session.send_text(text)


def _fields(args: dict[str, Any] | list[Any] | None, goal_type: type[Message]) -> dict[str, Any]:
    """``args`` as the goal's fields: an object as it is, a list in field order (rosbridge's)."""
    if args is None:
        return {}
    if isinstance(args, list):
        names = list(goal_type.model_fields)
        if len(args) > len(names):
            raise _GoalFailed(f"{len(args)} args for {len(names)} goal fields ({', '.join(names)})")
        return dict(zip(names, args, strict=False))
    return args
