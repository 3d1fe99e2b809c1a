"""The client side of a ROS 2 action: goals sent, their feedback and status followed, results
and cancels asked for, as rclpy's ActionClient does, over an :class:`ActionTransport`.

    client = ActionClient(NodeTransport(node), Fibonacci, "/fibonacci")
    await client.wait_for_server(timeout_s=5)
    goal = await client.send_goal(Fibonacci.Goal(order=5), on_feedback=print)
    if goal.accepted:
        response = await client.get_result(goal)      # GetResult.Response: status, result

Feedback and status come on the action's topics, read from the moment the client exists, and
go to the goal they name. ``wait_for_server`` waits until the three services are served and
both topics are linked, so the first feedback of a goal sent after it is never lost. Everything
here runs on the event loop; callbacks are called there and must be quick (the rclpy façade
hands them to the program's executor).
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import Any

from services.runtime.actions.goals import TERMINAL_STATUSES, GoalStatusCode, new_goal_id
from services.runtime.actions.messages import action_messages
from services.runtime.actions.names import ActionNames
from services.runtime.actions.transport import ActionTransport
from services.runtime.errors import ServiceTimeoutError
from shared_models import ActionType, Message, ServiceType

__all__ = ["ActionClient", "ClientGoal"]

_READY_POLL_S = 0.05
_RESULT_CALL_TIMEOUT_S = 300.0  # one get_result call; a goal running longer is asked again
# send_goal and cancel_goal wait for the server's callbacks, which wait for its executor: one
# busy with a long goal (rclpy.spin's single thread) answers when it ends. ROS waits for ever.
_CALL_TIMEOUT_S = 300.0


class ClientGoal:
    """A goal this client sent: its ID, the server's answer, its latest status."""

    def __init__(
        self,
        goal_id: bytes,
        on_feedback: Callable[[Any], None] | None,
        on_status: Callable[[ClientGoal], None] | None,
    ) -> None:
        self.goal_id = goal_id
        self.accepted = False
        self.stamp: Message | None = None
        self.status = GoalStatusCode.UNKNOWN
        self.on_feedback = on_feedback
        self.on_status = on_status

    def __repr__(self) -> str:
        return f"ClientGoal <id={self.goal_id.hex()}, accepted={self.accepted}, status={self.status}>"


class ActionClient:
    """Sends goals to one action (see the module docstring); ``name`` is resolved."""

    def __init__(self, transport: ActionTransport, action_type: type[ActionType], name: str) -> None:
        if not (isinstance(action_type, type) and issubclass(action_type, ActionType) and action_type.__ros_type__):
            raise TypeError(f"an action client needs an action type such as example_interfaces.action.Fibonacci, got {action_type!r}")
        self.action_type = action_type
        self.names = ActionNames(name)
        self._transport = transport
        self._messages = messages = action_messages()
        self._services: tuple[tuple[str, type[ServiceType]], ...] = (
            (self.names.send_goal, action_type.SendGoal),
            (self.names.cancel_goal, messages.CancelGoal),
            (self.names.get_result, action_type.GetResult),
        )
        self._goals: dict[bytes, ClientGoal] = {}
        transport.subscribe(self.names.feedback, action_type.FeedbackMessage, self._feedback)
        transport.subscribe(self.names.status, messages.GoalStatusArray, self._status)

    # -- the server ---------------------------------------------------------------------------

    async def server_is_ready(self) -> bool:
        """Whether a server serves the action and its topics reach this client."""
        transport = self._transport
        return transport.linked(self.names.feedback) and transport.linked(self.names.status) and await transport.served(self._services)

    async def wait_for_server(self, timeout_s: float | None = None) -> bool:
        """Wait until :meth:`server_is_ready`; False if ``timeout_s`` passes first (None: for ever)."""
        try:
            async with asyncio.timeout(timeout_s):
                while not await self.server_is_ready():
                    await asyncio.sleep(_READY_POLL_S)
        except TimeoutError:
            return False
        return True

    # -- goals --------------------------------------------------------------------------------

    async def send_goal(
        self,
        goal: Message,
        *,
        goal_id: bytes | None = None,
        on_feedback: Callable[[Any], None] | None = None,
        on_status: Callable[[ClientGoal], None] | None = None,
        timeout_s: float = _CALL_TIMEOUT_S,
    ) -> ClientGoal:
        """Send ``goal`` (the action's Goal); the returned goal says whether it was accepted.
        ``on_feedback(FeedbackMessage)`` and ``on_status(goal)`` follow it until its result."""
        if not isinstance(goal, self.action_type.Goal):
            raise TypeError(f"{self.names.name} takes {self.action_type.__ros_type__} goals ({self.action_type.Goal.__name__}), got {type(goal).__name__}")
        goal_id = goal_id or new_goal_id()
        tracked = ClientGoal(goal_id, on_feedback, on_status)
        self._goals[goal_id] = tracked  # before the answer: feedback may come first
        request = self.action_type.SendGoal.Request(goal_id=self._messages.UUID(uuid=goal_id), goal=goal)
        try:
            response = await self._transport.call(self.names.send_goal, self.action_type.SendGoal, request, timeout_s)
        except BaseException:
            self._goals.pop(goal_id, None)
            raise
        tracked.accepted, tracked.stamp = response.accepted, response.stamp
        if not tracked.accepted:
            self._goals.pop(goal_id, None)
        elif tracked.status == GoalStatusCode.UNKNOWN:
            tracked.status = GoalStatusCode.ACCEPTED
        return tracked

    async def get_result(self, goal: ClientGoal) -> Any:
        """The goal's GetResult response (``status``, ``result``), once it has one; feedback
        for it stops then."""
        request = self.action_type.GetResult.Request(goal_id=self._messages.UUID(uuid=goal.goal_id))
        while True:
            try:
                response = await self._transport.call(
                    self.names.get_result, self.action_type.GetResult, request, _RESULT_CALL_TIMEOUT_S
                )
            except ServiceTimeoutError:
                continue  # still running: ask again
            break
        self._goals.pop(goal.goal_id, None)
        if response.status != GoalStatusCode.UNKNOWN:
            self._set_status(goal, response.status)
        return response

    async def cancel(self, goal: ClientGoal | None = None, *, timeout_s: float = _CALL_TIMEOUT_S) -> Any:
        """Ask the server to cancel ``goal`` (None: every goal it holds); its CancelGoal response."""
        messages = self._messages
        info = messages.GoalInfo()
        if goal is not None:
            info.goal_id = messages.UUID(uuid=goal.goal_id)
        request = messages.CancelGoal.Request(goal_info=info)
        return await self._transport.call(self.names.cancel_goal, messages.CancelGoal, request, timeout_s)

    def close(self) -> None:
        """Stop following goals."""
        self._goals.clear()
        self._transport.close()

    # -- the topics ---------------------------------------------------------------------------

    def _feedback(self, message: Any) -> None:
        goal = self._goals.get(bytes(message.goal_id.uuid))
        if goal is not None and goal.on_feedback is not None:
            goal.on_feedback(message)

    def _status(self, message: Any) -> None:
        for line in message.status_list:
            goal = self._goals.get(bytes(line.goal_info.goal_id.uuid))
            if goal is not None:
                self._set_status(goal, line.status)

    def _set_status(self, goal: ClientGoal, status: int) -> None:
        if status == goal.status or goal.status in TERMINAL_STATUSES:
            return
        goal.status = status
        if goal.on_status is not None:
            goal.on_status(goal)
