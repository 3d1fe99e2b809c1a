"""rosbridge's ``advertise_action``: a client serves a ROS 2 action, which the core hosts for it.

    -> {"op": "advertise_action", "action": "/fibonacci", "type": "example_interfaces/action/Fibonacci"}
    <- {"op": "send_action_goal", "id": "action_goal:/fibonacci:1", "action": "/fibonacci",
        "action_type": "example_interfaces/action/Fibonacci", "args": {"order": 5}, "feedback": true}
    -> {"op": "action_feedback", "id": "action_goal:/fibonacci:1", "action": "/fibonacci", "values": {"sequence": [0, 1]}}
    -> {"op": "action_result", "id": "action_goal:/fibonacci:1", "action": "/fibonacci",
        "values": {"sequence": [0, 1, 1, 2, 3, 5]}, "status": 4, "result": true}
    <- {"op": "cancel_action_goal", "id": "action_goal:/fibonacci:1", "action": "/fibonacci"}
    -> {"op": "unadvertise_action", "action": "/fibonacci"}

As rosbridge_suite's capability serves it: the core is the action's server in the graph (ROS
2's ``_action`` services and topics, the SDK's :class:`~services.runtime.actions.server.ActionServer`
on the client's guest node), accepts every goal and hands it to the client with an id of its
own; a cancel request is accepted and passed on, and the goal ends when the client says how
(``action_result``: ``status`` 4 succeeded, 5 cancelled (after a cancel request), 6 or
``result: false`` aborted). Goals still running when the client unadvertises the action or
leaves are aborted.
"""

from __future__ import annotations

import asyncio
import itertools
import json
from typing import Any

from pydantic import Field, ValidationError

from services.access import Verb
from services.protocols.ops import Refused, describe_error
from services.protocols.rosbridge.core_host import CoreHost
from services.protocols.rosbridge.frames import Status
from services.protocols.rosbridge.ops import RosbridgeOp
from services.protocols.session import ClientSession
from services.runtime.actions.goals import GoalEvent, GoalStatusCode
from services.runtime.actions.names import ActionNames
from services.runtime.actions.server import ActionServer, ServerGoal
from shared_models import ActionType, Message, get_interface, resolve_name

__all__ = ["ActionFeedback", "ActionResult", "AdvertiseAction", "HostedActions", "UnadvertiseAction"]


class AdvertiseAction(RosbridgeOp):
    action: str
    type: str


class UnadvertiseAction(RosbridgeOp):
    action: str


class ActionFeedback(RosbridgeOp):
    id: str | int
    action: str
    values: dict[str, Any] = Field(default_factory=dict)


class ActionResult(RosbridgeOp):
    id: str | int
    action: str
    values: Any = None
    status: int = GoalStatusCode.SUCCEEDED
    result: bool = True


class _HostedAction:
    """One action a client serves: its server in the core, and the goals it runs for it."""

    def __init__(self, session: ClientSession, name: str, type_name: str, action_type: type[ActionType]) -> None:
        self.name = name
        self.type_name = type_name
        self.action_type = action_type
        self._session = session
        self._ids = itertools.count(1)
        self.goals: dict[str, ServerGoal] = {}  # the client's goal id -> the goal
        self._sending: asyncio.Future[None] | None = None  # ops to the client, in order
        self._host = CoreHost(session.access, session.guest)
        self.server = ActionServer(
            self._host, action_type, name, on_goal=self._accept, on_cancel=self._cancel, on_accepted=self._run
        )

    async def _accept(self, goal: Message) -> bool:
        return True  # as rosbridge_suite's server: the client decides nothing before it runs

    def _run(self, goal: ServerGoal) -> None:
        goal.execute()
        goal_id = f"action_goal:{self.name}:{next(self._ids)}"
        self.goals[goal_id] = goal
        self._send({
            "op": "send_action_goal", "id": goal_id, "action": self.name, "action_type": self.type_name,
            "args": goal.request.model_dump(mode="json"), "feedback": True,
        })  # fmt: skip

    async def _cancel(self, goal: ServerGoal) -> bool:
        goal_id = next((key for key, held in self.goals.items() if held is goal), None)
        if goal_id is not None:
            self._send({"op": "cancel_action_goal", "id": goal_id, "action": self.name})
        return True

    def _send(self, message: dict[str, Any]) -> None:
        previous = self._sending
        text = json.dumps(message)

        async def in_turn() -> None:
            if previous is not None:
                await previous
            await self._session.send_text(text)

        self._sending = asyncio.ensure_future(in_turn())

    def feedback(self, op: ActionFeedback) -> bool:
        goal = self.goals.get(str(op.id))
        if goal is None:
            return False
        try:
            feedback = self.action_type.Feedback.model_validate(op.values)
        except ValidationError as error:
            raise Refused(describe_error("action_feedback", error)) from None
        goal.publish_feedback(feedback)
        return True

    def result(self, op: ActionResult) -> bool:
        goal = self.goals.get(str(op.id))
        if goal is None:
            return False
        values = op.values if isinstance(op.values, dict) else {}
        try:
            result = self.action_type.Result.model_validate(values)
        except ValidationError as error:
            raise Refused(describe_error("action_result", error)) from None
        del self.goals[str(op.id)]
        if op.result and op.status == GoalStatusCode.SUCCEEDED and goal.is_active:
            goal.update(GoalEvent.SUCCEED)
        elif op.result and op.status == GoalStatusCode.CANCELED and goal.status == GoalStatusCode.CANCELING:
            goal.update(GoalEvent.CANCELED)
        goal.finish(result)  # anything else: aborted, as rclpy ends a goal its callback left running
        return True

    def close(self) -> None:
        """The client serves it no more: goals still running are aborted, the server goes."""
        for goal in self.goals.values():
            goal.finish(self.action_type.Result())
        self.goals.clear()
        self.server.close()
        self._host.close()


class HostedActions:
    """The actions one connection serves (see the module docstring)."""

    def __init__(self, session: ClientSession, status: Status) -> None:
        self._session = session
        self._status = status
        self._actions: dict[str, _HostedAction] = {}

    async def advertise(self, op: AdvertiseAction) -> None:
        name = resolve_name(op.action)
        # Serving an action is serving its services (under its name): a student's, under /NAME.
        self._session.visitor.check(Verb.SERVE, name)
        action_type = get_interface(op.type)
        if not (isinstance(action_type, type) and issubclass(action_type, ActionType)):
            raise Refused(f"{op.type} is not an action type (example_interfaces/action/Fibonacci is one)")
        served = self._session.access.registry.service(ActionNames(name).send_goal)
        if served is not None and name not in self._actions:
            raise Refused(f"{name} is already served by {served[1].description.name}")
        if name in self._actions:
            self._actions.pop(name).close()
        self._actions[name] = _HostedAction(self._session, name, op.type, action_type)
        await self._status("info", f"serving the action {name} ({op.type})", op.id)

    async def unadvertise(self, op: UnadvertiseAction) -> None:
        name = resolve_name(op.action)
        action = self._actions.pop(name, None)
        if action is None:
            await self._status("warning", f"{name} is not an action this client serves", op.id)
            return
        action.close()

    async def feedback(self, op: ActionFeedback) -> None:
        action = self._actions.get(resolve_name(op.action))
        if action is None or not action.feedback(op):
            await self._status("warning", f"action_feedback for {op.id!r}: no goal of {op.action} with this id is running", op.id)

    async def result(self, op: ActionResult) -> None:
        action = self._actions.get(resolve_name(op.action))
        if action is None or not action.result(op):
            await self._status("warning", f"action_result for {op.id!r}: no goal of {op.action} with this id is running", op.id)

    def close(self) -> None:
        for action in self._actions.values():
            action.close()
        self._actions.clear()
