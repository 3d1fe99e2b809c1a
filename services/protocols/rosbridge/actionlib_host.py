"""ROS 1's actionlib protocol, server side, served by the core for a guest (tf2_web_republisher's action).

    NAME/goal      XActionGoal      read: header, goal_id, goal
    NAME/cancel    actionlib_msgs/GoalID (an ID, a stamp, or neither: every goal)
    NAME/status    actionlib_msgs/GoalStatusArray, latched, at each change
    NAME/feedback  XActionFeedback  header, status, feedback
    NAME/result    XActionResult    header, status, result

The topics a rosbridge client's ``ROSLIB.ActionClient`` (or roslibpy's ``actionlib``) reads and
writes. The rospy façade has actionlib's whole server (:mod:`services.ros.actionlib`); this is the
part a server in the core needs, on a :class:`~.core_host.CoreHost` and its event loop: a goal
is accepted (ACTIVE) or rejected with why, runs until its owner ends it (:meth:`finish`) or a
cancel picks it (by ID, by stamp: every goal stamped at or before it, or all; it is then
PREEMPTED and ``on_cancel`` told), and an ended goal stays in the status list 5 s, as
actionlib's ``status_list_timeout``.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import Any

import services.protocols.rosbridge.clock as clock
from services.protocols.rosbridge.core_host import CoreHost
from services.runtime.actions.messages import actionlib_messages
from shared_models import Message, get_interface
from shared_models.std_msgs import Header

__all__ = ["ActionlibHost"]

_STATUS_LIST_TIMEOUT_S = 5.0
_QUEUE_SIZE = 50


class ActionlibHost:
    """One ROS 1 action served in the core (see the module docstring).

    ``on_goal(goal_id, goal)`` answers why a goal is rejected, or None to accept it;
    ``on_cancel(goal_id)`` is told of a goal a cancel request ended.
    """

    def __init__(
        self, host: CoreHost, name: str, action_type: str, *,
        on_goal: Callable[[str, Any], str | None], on_cancel: Callable[[str], None],
    ) -> None:  # fmt: skip
        package, _, short = action_type.partition("/action/")
        envelope = f"{package}/msg/{short}Action"
        self._action_goal = _message_type(envelope + "Goal")
        self._action_feedback = _message_type(envelope + "Feedback")
        self._action_result = _message_type(envelope + "Result")
        self._result: Any = self._action_result.model_fields["result"].annotation
        self.feedback_type: Any = self._action_feedback.model_fields["feedback"].annotation  # the XFeedback
        self._host = host
        self._on_goal = on_goal
        self._on_cancel = on_cancel
        self._messages = actionlib_messages()
        self._statuses: dict[str, Any] = {}  # goal ID -> its actionlib_msgs/GoalStatus
        self._expiries: dict[str, asyncio.TimerHandle] = {}
        self._status = host.create_publisher(self._messages.GoalStatusArray, f"{name}/status", 1, latched=True)
        self.feedback_publisher = host.create_publisher(self._action_feedback, f"{name}/feedback", _QUEUE_SIZE)
        self._result_publisher = host.create_publisher(self._action_result, f"{name}/result", _QUEUE_SIZE)
        host.create_subscription(self._action_goal, f"{name}/goal", self._goal, _QUEUE_SIZE)
        host.create_subscription(self._messages.GoalID, f"{name}/cancel", self._cancel, _QUEUE_SIZE)

    def _header(self) -> Header:
        return Header(stamp=clock.now(self._host.access))

    def _goal(self, action_goal: Any) -> None:
        GoalStatus = self._messages.GoalStatus
        goal_id = action_goal.goal_id
        if not goal_id.id or goal_id.id in self._statuses:
            return  # actionlib ignores a goal it already holds
        if goal_id.stamp.to_nsec() == 0:
            goal_id = goal_id.model_copy(update={"stamp": self._header().stamp})
        status = GoalStatus(goal_id=goal_id, status=GoalStatus.PENDING)
        self._statuses[goal_id.id] = status
        reason = self._on_goal(goal_id.id, action_goal.goal)
        if reason is None:
            status.status = GoalStatus.ACTIVE
            self._publish_status()
        else:
            self._end(goal_id.id, GoalStatus.REJECTED, reason)

    def _cancel(self, request: Any) -> None:
        GoalStatus = self._messages.GoalStatus
        stamp_ns = request.stamp.to_nsec()
        picked = [
            goal_id for goal_id, status in self._statuses.items()
            if status.status == GoalStatus.ACTIVE and (
                (not request.id and stamp_ns == 0) or goal_id == request.id
                or (stamp_ns and status.goal_id.stamp.to_nsec() <= stamp_ns)
            )
        ]  # fmt: skip
        for goal_id in picked:
            self._on_cancel(goal_id)
            self._end(goal_id, GoalStatus.PREEMPTED, "cancelled by a client")

    def publish_feedback(self, goal_id: str, feedback: Message) -> None:
        status = self._statuses.get(goal_id)
        if status is not None:
            self.feedback_publisher.publish(self._action_feedback(header=self._header(), status=status, feedback=feedback))

    def finish(self, goal_id: str, text: str) -> None:
        """End an active goal from the server's side: aborted, with why."""
        status = self._statuses.get(goal_id)
        if status is not None and status.status == self._messages.GoalStatus.ACTIVE:
            self._end(goal_id, self._messages.GoalStatus.ABORTED, text)

    def _end(self, goal_id: str, code: int, text: str) -> None:
        status = self._statuses[goal_id]
        status.status, status.text = code, text
        self._result_publisher.publish(self._action_result(header=self._header(), status=status, result=self._result()))
        self._publish_status()
        loop = asyncio.get_running_loop()
        self._expiries[goal_id] = loop.call_later(_STATUS_LIST_TIMEOUT_S, self._expire, goal_id)

    def _expire(self, goal_id: str) -> None:
        self._expiries.pop(goal_id, None)
        if self._statuses.pop(goal_id, None) is not None:
            self._publish_status()

    def _publish_status(self) -> None:
        array = self._messages.GoalStatusArray(header=self._header(), status_list=list(self._statuses.values()))
        self._status.publish(array)

    def close(self) -> None:
        for handle in self._expiries.values():
            handle.cancel()
        self._expiries.clear()


def _message_type(name: str) -> Any:
    """An envelope type made from the .action file: its fields are used by name, so typed loosely."""
    found = get_interface(name)
    if not (isinstance(found, type) and issubclass(found, Message)):
        raise TypeError(f"{name} is not a message type")
    return found
