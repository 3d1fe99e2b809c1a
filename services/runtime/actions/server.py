"""The server side of a ROS 2 action, on a node: ROS 2's protocol over Skydeck's services and topics.

    server = ActionServer(node, Fibonacci, "fibonacci", on_goal=accept, on_cancel=agree,
                          on_accepted=lambda goal: start(goal))

It serves ``NAME/_action/send_goal``, ``cancel_goal`` and ``get_result`` and publishes
``feedback`` and ``status`` (latched), with ROS 2's types (:mod:`.names`). What it decides is
ROS 2's: a goal ID already held is refused; a cancel request picks goals as rcl_action does (one
by ID, those accepted at or before a stamp, or all) and answers ``ERROR_REJECTED`` when every goal
it picked was refused by ``on_cancel``; ``get_result`` answers when the goal has its result
(``UNKNOWN`` for a goal it does not hold); the status array, published at each transition, lists
every goal held, and a goal is forgotten ``result_timeout_s`` after its result is set (ROS 2 since
Jazzy keeps it 10 s after it ends).

The server runs on a node, or on anything that offers what it uses of one (:class:`ActionHost`:
the core hosts an action a rosbridge client serves). Policy is the caller's (the rclpy façade
hands its callbacks to the program's executor):
``on_goal(goal) -> bool`` accepts a goal, ``on_cancel(goal) -> bool`` agrees to cancel one,
``on_accepted(goal)`` is told of each goal accepted (it calls ``goal.execute()`` when it runs it).
Everything here runs on the node's event loop.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable
from typing import Any, Protocol

from services.runtime.actions.goals import (
    ACTIVE_STATUSES,
    GoalEvent,
    GoalStatusCode,
    goal_id_text,
    next_status,
)
from services.runtime.actions.messages import action_messages
from services.runtime.actions.names import ActionNames
from shared_models import ActionType, Message, ServiceType

__all__ = ["ActionHost", "ActionServer", "ServerGoal"]

logger = logging.getLogger("skydeck.runtime")

_FEEDBACK_DEPTH = 10  # rclpy's feedback publisher: QoSProfile(depth=10)
DEFAULT_RESULT_TIMEOUT_S = 10.0


class ActionHost(Protocol):
    """What an action server uses of the node it runs on (an SDK :class:`~services.runtime.node.Node` is one)."""

    def resolve_topic_name(self, topic: str) -> str: ...

    def create_publisher(self, msg_type: type[Any], topic: str, qos_profile: int = 10, *, latched: bool = False) -> Any: ...

    def create_service(self, srv_type: type[ServiceType], srv_name: str, callback: Callable[..., Any]) -> Any: ...

    def get_clock(self) -> Any: ...


class ServerGoal:
    """One goal the server holds: its info (ID and acceptance stamp), request and status."""

    def __init__(self, server: ActionServer, info: Message, request: Message) -> None:
        self.server = server
        self.info = info
        self.request = request
        self.status = GoalStatusCode.ACCEPTED
        self.result: Message | None = None  # the GetResult response, once the goal has it
        self._result_set = asyncio.get_running_loop().create_future()

    @property
    def goal_id(self) -> bytes:
        return bytes(self.info.goal_id.uuid)  # type: ignore[attr-defined]

    @property
    def is_active(self) -> bool:
        return self.status in ACTIVE_STATUSES

    @property
    def is_cancelable(self) -> bool:
        """Whether a cancel request can still move it (rcl_action: accepted or executing)."""
        return self.status in (GoalStatusCode.ACCEPTED, GoalStatusCode.EXECUTING)

    def update(self, event: GoalEvent) -> None:
        """Move the goal by ``event`` (GoalTransitionError if ROS 2 forbids it); the status
        array is published."""
        self.status = next_status(self.status, event)
        self.server.publish_status()

    def execute(self) -> None:
        """Start executing, unless a cancel came first (the goal then stays CANCELING, as rclpy
        lets the execute callback end it)."""
        if self.status != GoalStatusCode.CANCELING:
            self.update(GoalEvent.EXECUTE)

    def publish_feedback(self, feedback: Message) -> None:
        """Publish ``feedback`` (the action's Feedback) for this goal."""
        message = self.server.action_type.FeedbackMessage(goal_id=self.info.goal_id, feedback=feedback)  # type: ignore[attr-defined]
        self.server.feedback_publisher.publish(message)

    def finish(self, result: Message) -> bool:
        """The goal's execution ended with ``result``: clients waiting for it get it. A goal
        still active is aborted first (as rclpy does); returns whether it was."""
        aborted = self.is_active
        if aborted:
            self.update(GoalEvent.ABORT)
        self.result = self.server.action_type.GetResult.Response(status=self.status, result=result)
        if not self._result_set.done():
            self._result_set.set_result(self.result)
        self.server.expire_later(self)
        return aborted

    async def wait_for_result(self) -> Message:
        return await asyncio.shield(self._result_set)


class ActionServer:
    """Serves one action on ``node`` (see the module docstring)."""

    def __init__(
        self,
        node: ActionHost,
        action_type: type[ActionType],
        name: str,
        *,
        on_goal: Callable[[Message], Awaitable[bool]],
        on_cancel: Callable[[ServerGoal], Awaitable[bool]],
        on_accepted: Callable[[ServerGoal], None],
        result_timeout_s: float = DEFAULT_RESULT_TIMEOUT_S,
    ) -> None:
        if not (isinstance(action_type, type) and issubclass(action_type, ActionType) and action_type.__ros_type__):
            raise TypeError(f"an action server needs an action type such as example_interfaces.action.Fibonacci, got {action_type!r}")
        if not result_timeout_s >= 0:
            raise ValueError(f"result_timeout must be 0 or more seconds, got {result_timeout_s!r}")
        self.node = node
        self.action_type = action_type
        self.names = ActionNames(node.resolve_topic_name(name))
        self.goals: dict[bytes, ServerGoal] = {}
        self._on_goal = on_goal
        self._on_cancel = on_cancel
        self._on_accepted = on_accepted
        self._result_timeout_s = result_timeout_s
        self._expiries: dict[bytes, asyncio.TimerHandle] = {}
        self._messages = messages = action_messages()
        self.feedback_publisher = node.create_publisher(action_type.FeedbackMessage, self.names.feedback, _FEEDBACK_DEPTH)
        self.status_publisher = node.create_publisher(messages.GoalStatusArray, self.names.status, 1, latched=True)
        node.create_service(action_type.SendGoal, self.names.send_goal, self._send_goal)
        node.create_service(messages.CancelGoal, self.names.cancel_goal, self._cancel_goal)
        node.create_service(action_type.GetResult, self.names.get_result, self._get_result)

    # -- the three services -------------------------------------------------------------------

    async def _send_goal(self, request: Any) -> Any:
        goal_id = bytes(request.goal_id.uuid)
        accepted = False
        if goal_id in self.goals:
            logger.error("%s: a goal request came with the ID of a goal it holds (%s); refused", self.names.name, goal_id_text(goal_id))
        else:
            accepted = await self._on_goal(request.goal)
        response: Any = self.action_type.SendGoal.Response(accepted=accepted)
        if not accepted or goal_id in self.goals:  # (the same ID twice at once: the first wins)
            response.accepted = False
            return response
        info = self._messages.GoalInfo(goal_id=request.goal_id, stamp=self.node.get_clock().now().to_msg())
        goal = ServerGoal(self, info, request.goal)
        self.goals[goal_id] = goal
        response.stamp = info.stamp
        self.publish_status()
        # After the answer is on its way, as rclpy calls it once the response is sent.
        asyncio.get_running_loop().call_soon(self._on_accepted, goal)
        return response

    async def _cancel_goal(self, request: Any) -> Message:
        codes = self._messages.CancelGoal.Response
        response, picked = self._pick_for_cancel(request.goal_info)
        agreed = []
        for goal in picked:
            # (a goal that ended while the callback ran is left as it is, and not listed)
            if await self._on_cancel(goal) and goal.is_cancelable:
                goal.update(GoalEvent.CANCEL_GOAL)
                agreed.append(goal.info)
        if picked and not agreed:
            response.return_code = codes.ERROR_REJECTED
        response.goals_canceling = agreed
        return response

    def _pick_for_cancel(self, goal_info: Any) -> tuple[Any, list[ServerGoal]]:
        """rcl_action's choice: an ID alone picks that goal (UNKNOWN_GOAL_ID, or GOAL_TERMINATED
        when it ended); a stamp picks every active goal accepted at or before it (and the ID's);
        neither picks every active goal."""
        codes = self._messages.CancelGoal.Response
        response = codes(return_code=codes.ERROR_NONE)
        goal_id = bytes(goal_info.goal_id.uuid)
        stamp_ns = goal_info.stamp.to_nsec()
        no_id = goal_id == bytes(16)
        if not no_id and stamp_ns == 0:
            goal = self.goals.get(goal_id)
            if goal is None:
                response.return_code = codes.ERROR_UNKNOWN_GOAL_ID
                return response, []
            if not goal.is_cancelable:  # (rcl's word for a goal ended or already cancelling)
                response.return_code = codes.ERROR_GOAL_TERMINATED
                return response, []
            return response, [goal]
        if no_id and stamp_ns == 0:
            return response, [goal for goal in self.goals.values() if goal.is_cancelable]
        picked = [
            goal for goal in self.goals.values()
            if goal.is_cancelable and (goal.info.stamp.to_nsec() <= stamp_ns or goal.goal_id == goal_id)  # type: ignore[attr-defined]
        ]  # fmt: skip
        return response, picked

    async def _get_result(self, request: Any) -> Message:
        goal = self.goals.get(bytes(request.goal_id.uuid))
        if goal is None:
            return self.action_type.GetResult.Response(status=GoalStatusCode.UNKNOWN)
        return await goal.wait_for_result()

    # -- status and expiry --------------------------------------------------------------------

    def publish_status(self) -> None:
        """Publish every goal held and its status (latched: a late client gets it at once)."""
        messages = self._messages
        statuses = [messages.GoalStatus(goal_info=goal.info, status=goal.status) for goal in self.goals.values()]
        self.status_publisher.publish(messages.GoalStatusArray(status_list=statuses))

    def expire_later(self, goal: ServerGoal) -> None:
        """Forget ``goal`` ``result_timeout_s`` from now (its result and its status line)."""
        handle = asyncio.get_running_loop().call_later(self._result_timeout_s, self._expire, goal.goal_id)
        self._expiries[goal.goal_id] = handle

    def _expire(self, goal_id: bytes) -> None:
        self._expiries.pop(goal_id, None)
        if self.goals.pop(goal_id, None) is not None:
            self.publish_status()

    def close(self) -> None:
        """Stop the expiry timers (the node is going)."""
        for handle in self._expiries.values():
            handle.cancel()
        self._expiries.clear()
