"""``rclpy.action.ActionClient``: goals sent to a ROS 2 action, as the course writes it.

    self._action_client = ActionClient(self, Fibonacci, 'fibonacci')
    self._action_client.wait_for_server()
    future = self._action_client.send_goal_async(goal, feedback_callback=self.feedback_callback)
    future.add_done_callback(self.goal_response_callback)       # goal_handle.accepted, ...
    ...
    goal_handle.get_result_async().add_done_callback(self.get_result_callback)  # .result().result

The protocol is the SDK's :class:`services.runtime.actions.ActionClient` on the bridge's loop.
Feedback callbacks run in the executor spinning the node, in the client's callback group;
futures complete from the loop and their done callbacks run in the executor too, as rclpy's.
The blocking forms (``send_goal``, ``get_result``, ``cancel_goal``, ``wait_for_server``) work
from any thread, inside a callback too (rclpy deadlocks there): nothing waits for the executor.
"""

from __future__ import annotations

import concurrent.futures
from collections.abc import Callable, Coroutine
from typing import TYPE_CHECKING, Any

from services.ros.bridge import bridge
from services.ros.rclpy.callback_groups import CallbackGroup
from services.ros.rclpy.task import Future
from services.ros.rclpy.waitable import JobQueue, run_callback
from services.runtime.actions.client import ActionClient as LoopActionClient
from services.runtime.actions.client import ClientGoal
from services.runtime.actions.goals import new_goal_id
from services.runtime.actions.messages import action_messages
from services.runtime.actions.transport import NodeTransport
from shared_models import ActionType, Message

if TYPE_CHECKING:
    from services.ros.rclpy.node import Node

__all__ = ["ActionClient", "ClientGoalHandle"]


class ClientGoalHandle:
    """A goal sent: ``accepted``, ``goal_id``, ``stamp``, ``status``; its result and cancel."""

    def __init__(self, client: ActionClient, goal: ClientGoal, goal_id: Any) -> None:
        self._client = client
        self._goal = goal
        self._goal_id = goal_id

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ClientGoalHandle) and self._goal is other._goal

    def __hash__(self) -> int:
        return hash(self._goal.goal_id)

    def __repr__(self) -> str:
        return f"ClientGoalHandle <id={list(self._goal.goal_id)}, accepted={self.accepted}, status={self.status}>"

    @property
    def goal_id(self) -> Any:
        """Its ``unique_identifier_msgs/UUID``."""
        return self._goal_id

    @property
    def stamp(self) -> Any:
        """When the server accepted it (a ``builtin_interfaces/Time``)."""
        return self._goal.stamp

    @property
    def accepted(self) -> bool:
        return self._goal.accepted

    @property
    def status(self) -> int:
        """Its latest ``action_msgs/GoalStatus`` value, from the server's status topic."""
        return self._goal.status

    def get_result_async(self) -> Future:
        """A Future of the GetResult response (``.status``, ``.result``)."""
        return self._client._future(self._client._loop.get_result(self._goal))

    def get_result(self) -> Any:
        """Wait for the GetResult response."""
        return _wait(self.get_result_async())

    def cancel_goal_async(self) -> Future:
        """A Future of the CancelGoal response (``.return_code``, ``.goals_canceling``)."""
        return self._client._future(self._client._loop.cancel(self._goal))

    def cancel_goal(self) -> Any:
        """Ask to cancel, and wait for the CancelGoal response."""
        return _wait(self.cancel_goal_async())


class ActionClient(JobQueue):
    """Sends goals to one action from a node (see the module docstring)."""

    def __init__(
        self, node: Node, action_type: type[ActionType], action_name: str, *,
        callback_group: CallbackGroup | None = None, goal_service_qos_profile: Any = None,
        result_service_qos_profile: Any = None, cancel_service_qos_profile: Any = None,
        feedback_sub_qos_profile: Any = None, status_sub_qos_profile: Any = None,
    ) -> None:  # fmt: skip
        super().__init__(node, callback_group or node.default_callback_group, f"a feedback callback of the action client {action_name}")
        self._action_type = action_type
        runtime = node._rclpy_node
        self._loop = bridge.call(
            lambda: LoopActionClient(NodeTransport(runtime), action_type, runtime.resolve_topic_name(action_name))
        )
        self.action_name = self._loop.names.name
        node._rclpy_entities.append(self)

    @property
    def action_type(self) -> type[ActionType]:
        return self._action_type

    def server_is_ready(self) -> bool:
        """Whether a server of the action is there and its topics reach this client."""
        return bridge.run(self._loop.server_is_ready())

    def wait_for_server(self, timeout_sec: float | None = None) -> bool:
        """Wait until a server is ready; False if ``timeout_sec`` passes first (None: for ever)."""
        return bridge.run(self._loop.wait_for_server(timeout_sec))

    def send_goal_async(
        self, goal: Message, feedback_callback: Callable[[Any], Any] | None = None, goal_uuid: Any = None
    ) -> Future:
        """Send ``goal``; a Future of its ClientGoalHandle once the server answers.
        ``feedback_callback(feedback_msg)`` gets each FeedbackMessage (``.feedback``) for it."""
        self._check_goal(goal)
        goal_id = bytes(goal_uuid.uuid) if goal_uuid is not None else new_goal_id()
        on_feedback = None
        if feedback_callback is not None:
            on_feedback = lambda message: self.put(lambda: run_callback(feedback_callback, message))  # noqa: E731
        uuid = action_messages().UUID(uuid=goal_id)
        sent = self._loop.send_goal(goal, goal_id=goal_id, on_feedback=on_feedback)
        return self._future(sent, lambda tracked: ClientGoalHandle(self, tracked, uuid))

    def send_goal(self, goal: Message, **kwargs: Any) -> Any:
        """Send ``goal`` and wait for its GetResult response (None if it was rejected)."""
        self._check_goal(goal)
        handle = _wait(self.send_goal_async(goal, **kwargs))
        if not handle.accepted:
            return None
        return handle.get_result()

    def destroy(self) -> None:
        """Follow no more goals."""
        bridge.call_soon(self._loop.close)

    # -- internals ----------------------------------------------------------------------------

    def _check_goal(self, goal: Any) -> None:
        if not isinstance(goal, self._action_type.Goal):
            raise TypeError(
                f"{self.action_name} takes {self._action_type.__ros_type__} goals "
                f"({self._action_type.Goal.__name__}), got {type(goal).__name__}"
            )

    def _future(self, coroutine: Coroutine[Any, Any, Any], convert: Callable[[Any], Any] = lambda value: value) -> Future:
        """An rclpy Future completed by ``coroutine`` on the loop; done callbacks in the executor."""
        future = Future()
        future._dispatch = self._node._rclpy_dispatch
        running = bridge.submit(coroutine)

        def finished(outcome: concurrent.futures.Future[Any]) -> None:
            if outcome.cancelled():
                future.cancel()
            elif outcome.exception() is not None:
                future.set_exception(outcome.exception())  # type: ignore[arg-type]
            else:
                future.set_result(convert(outcome.result()))

        running.add_done_callback(finished)
        return future


def _wait(future: Future) -> Any:
    future.wait()
    return future.result()
