"""``rclpy.action.ActionServer``: a ROS 2 action served by a node, as the course writes one.

    self._action_server = ActionServer(self, Fibonacci, 'fibonacci', self.execute_callback,
                                       cancel_callback=self.cancel_callback)

    def execute_callback(self, goal_handle):
        feedback = Fibonacci.Feedback(sequence=[0, 1])
        for i in range(1, goal_handle.request.order):
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                return Fibonacci.Result()
            feedback.sequence.append(feedback.sequence[i] + feedback.sequence[i - 1])
            goal_handle.publish_feedback(feedback)
            time.sleep(1)
        goal_handle.succeed()
        return Fibonacci.Result(sequence=feedback.sequence)

The protocol (services, topics, goal states, cancel rules, results kept and expired) is the SDK's
:class:`services.runtime.actions.ActionServer` on the bridge's loop. Here are rclpy's callbacks
and threads: the goal, cancel and accepted callbacks run in the executor spinning the node, in
the server's callback group (the node's default unless given one); each execute callback runs
there too, outside any group, as rclpy runs it as a task: under a MultiThreadedExecutor several
goals execute at once and cancel requests are answered while they do; under a
SingleThreadedExecutor a sleeping execute callback holds the executor, as in ROS 2.
"""

from __future__ import annotations

from collections.abc import Callable
from enum import Enum
from typing import TYPE_CHECKING, Any

from services.ros.bridge import Bridge, bridge
from services.ros.rclpy.callback_groups import CallbackGroup
from services.ros.rclpy.waitable import JobQueue, run_callback
from services.runtime.actions.goals import GoalEvent, GoalStatusCode, goal_id_text
from services.runtime.actions.server import DEFAULT_RESULT_TIMEOUT_S, ServerGoal
from services.runtime.actions.server import ActionServer as LoopActionServer
from shared_models import ActionType, Message

if TYPE_CHECKING:
    from services.ros.rclpy.node import Node

__all__ = [
    "ActionServer",
    "CancelResponse",
    "GoalEvent",
    "GoalResponse",
    "ServerGoalHandle",
    "default_cancel_callback",
    "default_goal_callback",
    "default_handle_accepted_callback",
]


class GoalResponse(Enum):
    """What a goal callback answers."""

    REJECT = 1
    ACCEPT = 2


class CancelResponse(Enum):
    """What a cancel callback answers."""

    REJECT = 1
    ACCEPT = 2


def default_goal_callback(goal_request: Any) -> GoalResponse:
    """Accept every goal (rclpy's default)."""
    return GoalResponse.ACCEPT


def default_cancel_callback(goal_handle: Any) -> CancelResponse:
    """Refuse every cancel request (rclpy's default: give a cancel_callback to allow them)."""
    return CancelResponse.REJECT


def default_handle_accepted_callback(goal_handle: ServerGoalHandle) -> None:
    """Execute each goal as soon as it is accepted (rclpy's default)."""
    goal_handle.execute()


class ServerGoalHandle:
    """One goal the server accepted: ``request``, ``goal_id``, ``status``; the execute callback
    ends it with ``succeed()``, ``abort()`` or ``canceled()`` and returns its Result."""

    def __init__(self, server: ActionServer, goal: ServerGoal) -> None:
        self._server = server
        self._goal = goal

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ServerGoalHandle) and self._goal is other._goal

    def __hash__(self) -> int:
        return hash(self._goal.goal_id)

    def __repr__(self) -> str:
        return f"ServerGoalHandle <id={goal_id_text(self._goal.goal_id)}, status={self.status}>"

    @property
    def request(self) -> Any:
        """The goal the client sent (the action's Goal)."""
        return self._goal.request

    @property
    def goal_id(self) -> Any:
        """Its ``unique_identifier_msgs/UUID``."""
        return self._goal.info.goal_id  # type: ignore[attr-defined]

    @property
    def status(self) -> int:
        """Its ``action_msgs/GoalStatus`` value."""
        return self._goal.status

    @property
    def is_active(self) -> bool:
        return self._goal.is_active

    @property
    def is_cancel_requested(self) -> bool:
        return self._goal.status == GoalStatusCode.CANCELING

    def execute(self, execute_callback: Callable[[ServerGoalHandle], Any] | None = None) -> None:
        """Run the execute callback (this server's, or ``execute_callback``) for this goal."""
        bridge.call(self._goal.execute)
        self._server._start(self, execute_callback or self._server._execute_callback)

    def publish_feedback(self, feedback: Message) -> None:
        """Publish ``feedback`` (the action's Feedback) for this goal; never blocks."""
        feedback_type = self._server._action_type.Feedback
        if not isinstance(feedback, feedback_type):
            raise TypeError(f"publish_feedback takes {feedback_type.__name__} (the action's Feedback), got {type(feedback).__name__}")
        bridge.call_soon(self._goal.publish_feedback, feedback.model_copy(deep=True))

    def succeed(self) -> None:
        bridge.call(self._goal.update, GoalEvent.SUCCEED)

    def abort(self) -> None:
        bridge.call(self._goal.update, GoalEvent.ABORT)

    def canceled(self) -> None:
        bridge.call(self._goal.update, GoalEvent.CANCELED)

    def destroy(self) -> None:
        pass


class ActionServer(JobQueue):
    """Serves an action on a node (see the module docstring); rclpy's keywords are accepted."""

    def __init__(
        self, node: Node, action_type: type[ActionType], action_name: str,
        execute_callback: Callable[[ServerGoalHandle], Any] | None = None, *,
        callback_group: CallbackGroup | None = None,
        goal_callback: Callable[[Any], Any] = default_goal_callback,
        handle_accepted_callback: Callable[[ServerGoalHandle], Any] = default_handle_accepted_callback,
        cancel_callback: Callable[[ServerGoalHandle], Any] = default_cancel_callback,
        goal_service_qos_profile: Any = None, result_service_qos_profile: Any = None,
        cancel_service_qos_profile: Any = None, feedback_pub_qos_profile: Any = None,
        status_pub_qos_profile: Any = None, result_timeout: float = DEFAULT_RESULT_TIMEOUT_S,
    ) -> None:  # fmt: skip
        super().__init__(node, callback_group or node.default_callback_group, f"a callback of the action server {action_name}")
        for what, callback in (("goal_callback", goal_callback), ("cancel_callback", cancel_callback),
                               ("handle_accepted_callback", handle_accepted_callback)):  # fmt: skip
            if not callable(callback):
                raise TypeError(f"ActionServer's {what} must be a function, got {callback!r}")
        if execute_callback is not None and not callable(execute_callback):
            raise TypeError(f"ActionServer's execute_callback must be a function, got {execute_callback!r}")
        self._action_type = action_type
        self._execute_callback = execute_callback
        self._goal_callback = goal_callback
        self._cancel_callback = cancel_callback
        self._handle_accepted_callback = handle_accepted_callback
        self._handles: dict[bytes, ServerGoalHandle] = {}
        # Execute callbacks in no group: rclpy runs them as executor tasks, beside the server's.
        self._executions = JobQueue(node, None, f"the execute callback of the action server {action_name}")
        self._server = bridge.call(
            lambda: LoopActionServer(
                node._rclpy_node, action_type, action_name, on_goal=self._on_goal, on_cancel=self._on_cancel,
                on_accepted=self._on_accepted, result_timeout_s=result_timeout,
            )
        )  # fmt: skip
        self.action_name = self._server.names.name
        node._rclpy_entities.extend((self, self._executions))

    @property
    def action_type(self) -> type[ActionType]:
        return self._action_type

    def register_execute_callback(self, execute_callback: Callable[[ServerGoalHandle], Any]) -> None:
        if not callable(execute_callback):
            raise TypeError(f"execute_callback must be a function, got {execute_callback!r}")
        self._execute_callback = execute_callback

    def register_goal_callback(self, goal_callback: Callable[[Any], Any]) -> None:
        self._goal_callback = goal_callback

    def register_cancel_callback(self, cancel_callback: Callable[[ServerGoalHandle], Any]) -> None:
        self._cancel_callback = cancel_callback

    def register_handle_accepted_callback(self, handle_accepted_callback: Callable[[ServerGoalHandle], Any]) -> None:
        self._handle_accepted_callback = handle_accepted_callback

    def destroy(self) -> None:
        """Serve no more goals (the node keeps the names until it stops)."""
        bridge.call_soon(self._server.close)

    # -- the loop's side: decisions handed to the executor ------------------------------------

    async def _on_goal(self, goal: Message) -> bool:
        try:
            response = await Bridge.hand_off(self.put, lambda: self._call(self._goal_callback, goal))
        except Exception:
            return False  # its traceback was printed where it ran; refused, as a bad answer is
        if not isinstance(response, GoalResponse):
            self._node.get_logger().warning("Goal request callback did not return a GoalResponse type. Rejecting goal.")
            return False
        return response == GoalResponse.ACCEPT

    async def _on_cancel(self, goal: ServerGoal) -> bool:
        handle = self._handles.get(goal.goal_id) or ServerGoalHandle(self, goal)
        try:
            response = await Bridge.hand_off(self.put, lambda: self._call(self._cancel_callback, handle))
        except Exception:
            return False
        return response == CancelResponse.ACCEPT

    def _on_accepted(self, goal: ServerGoal) -> None:
        handle = self._handles[goal.goal_id] = ServerGoalHandle(self, goal)
        self.put(lambda: run_callback(self._handle_accepted_callback, handle))

    def _call(self, callback: Callable[..., Any], *args: Any) -> Any:
        """Run a user callback (in the executor); its exception is reported, then raised to the
        loop, which refuses what it was asked."""
        try:
            return run_callback(callback, *args)
        except Exception as error:
            self._node._rclpy_report(error, self.what)
            raise

    # -- executing a goal ---------------------------------------------------------------------

    def _start(self, handle: ServerGoalHandle, execute_callback: Callable[[ServerGoalHandle], Any] | None) -> None:
        if execute_callback is None:
            raise TypeError(f"the action server {self.action_name} has no execute_callback: give one to ActionServer()")
        self._executions.put(lambda: self._execute(handle, execute_callback))

    def _execute(self, handle: ServerGoalHandle, execute_callback: Callable[[ServerGoalHandle], Any]) -> None:
        result_type = self._action_type.Result
        try:
            result = run_callback(execute_callback, handle)
        except Exception as error:
            self._node._rclpy_report(error, self._executions.what)
            result = result_type()
        if not isinstance(result, result_type):
            self._node.get_logger().error(
                f"the execute callback of {self.action_name} returned {type(result).__name__}, not "
                f"{result_type.__name__}: the goal's result is empty"
            )
            result = result_type()
        if bridge.call(handle._goal.finish, result):
            self._node.get_logger().warning(f"Goal state not set, assuming aborted. Goal ID: {goal_id_text(handle._goal.goal_id)}")
        self._handles.pop(handle._goal.goal_id, None)
