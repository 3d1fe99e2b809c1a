"""``actionlib.ActionServer``: ROS 1's action protocol, server side, on the rospy façade.

    NAME/goal      XActionGoal      client -> server   (header, goal_id, goal)
    NAME/cancel    actionlib_msgs/GoalID               (an ID, a stamp, or neither: all)
    NAME/status    actionlib_msgs/GoalStatusArray      server -> client, latched, 5 times a second
    NAME/feedback  XActionFeedback  (header, status, feedback)
    NAME/result    XActionResult    (header, status, result)

Goals and their statuses are actionlib's (``PENDING -> ACTIVE -> SUCCEEDED``, ``RECALLING`` and
``PREEMPTING`` when a cancel comes, ...): a :class:`ServerGoalHandle` moves one, refusing with
actionlib's logged error a move its state does not allow. A cancel request picks goals by ID, by
stamp (everything at or before it) or all, as actionlib does; one for an ID not seen yet is
remembered, so the goal is recalled when it comes, and a goal stamped at or before the latest
cancel stamp is cancelled on arrival. A goal that ended stays in the status list 5 s
(``status_list_timeout``). Callbacks run on the subscribers' threads, under the server's lock.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from services.ros.actionlib.spec import goal_status, spec_types
from services.ros.rospy.core import process
from services.ros.rospy.log import logerr
from services.ros.rospy.rostime import Time
from services.ros.rospy.topics import Publisher, Subscriber
from services.runtime.actions.messages import actionlib_messages
from shared_models import Message

__all__ = ["ActionServer", "ServerGoalHandle"]

_STATUS_PERIOD_S = 0.2  # actionlib's status_frequency, 5 Hz
_STATUS_LIST_TIMEOUT_S = 5.0
_QUEUE_SIZE = 50


class _Tracker:
    """One goal's status line (and the goal, once it came)."""

    def __init__(self, status: Any, goal: Message | None) -> None:
        self.status = status  # an actionlib_msgs/GoalStatus
        self.goal = goal  # the ActionGoal envelope; None for a cancel that came first
        self.ended_at: float | None = None  # monotonic time it left the active states


class ServerGoalHandle:
    """One goal on an :class:`ActionServer`: its request, ID and status, and the moves that
    answer it (``set_accepted``, ``set_succeeded``, ...); an empty handle is ``ServerGoalHandle()``."""

    def __init__(self, tracker: _Tracker | None = None, server: ActionServer | None = None) -> None:
        self._tracker = tracker
        self._server = server

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ServerGoalHandle):
            return False
        if self._tracker is None or other._tracker is None:
            return self._tracker is other._tracker
        return self.get_goal_id().id == other.get_goal_id().id

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __hash__(self) -> int:
        return hash(self.get_goal_id().id) if self._tracker is not None else 0

    def get_goal(self) -> Message | None:
        """The goal (the action's Goal), or None for an empty handle."""
        if self._tracker is None or self._tracker.goal is None:
            return None
        return self._tracker.goal.goal  # type: ignore[attr-defined,no-any-return]

    def get_goal_id(self) -> Any:
        """Its ``actionlib_msgs/GoalID``."""
        if self._tracker is None:
            return actionlib_messages().GoalID()
        return self._tracker.status.goal_id

    def get_goal_status(self) -> Any:
        """Its ``actionlib_msgs/GoalStatus`` (``.status``, ``.text``)."""
        if self._tracker is None:
            return goal_status()()
        return self._tracker.status

    def set_accepted(self, text: str = "") -> None:
        GoalStatus = goal_status()
        self._move({GoalStatus.PENDING: GoalStatus.ACTIVE, GoalStatus.RECALLING: GoalStatus.PREEMPTING},
                   text, None, "an active state", "a pending or recalling state")  # fmt: skip

    def set_canceled(self, result: Message | None = None, text: str = "") -> None:
        GoalStatus = goal_status()
        moves = {GoalStatus.PENDING: GoalStatus.RECALLED, GoalStatus.RECALLING: GoalStatus.RECALLED,
                 GoalStatus.ACTIVE: GoalStatus.PREEMPTED, GoalStatus.PREEMPTING: GoalStatus.PREEMPTED}  # fmt: skip
        self._move(moves, text, result, "a cancelled state", "a pending, recalling, active, or preempting state")

    def set_rejected(self, result: Message | None = None, text: str = "") -> None:
        GoalStatus = goal_status()
        moves = {GoalStatus.PENDING: GoalStatus.REJECTED, GoalStatus.RECALLING: GoalStatus.REJECTED}
        self._move(moves, text, result, "a rejected state", "a pending or recalling state")

    def set_aborted(self, result: Message | None = None, text: str = "") -> None:
        GoalStatus = goal_status()
        moves = {GoalStatus.ACTIVE: GoalStatus.ABORTED, GoalStatus.PREEMPTING: GoalStatus.ABORTED}
        self._move(moves, text, result, "an aborted state", "a preempting or active state")

    def set_succeeded(self, result: Message | None = None, text: str = "") -> None:
        GoalStatus = goal_status()
        moves = {GoalStatus.ACTIVE: GoalStatus.SUCCEEDED, GoalStatus.PREEMPTING: GoalStatus.SUCCEEDED}
        self._move(moves, text, result, "a succeeded state", "a preempting or active state")

    def publish_feedback(self, feedback: Message) -> None:
        """Publish ``feedback`` (the action's Feedback) for this goal."""
        if self._tracker is None or self._server is None:
            logerr("Attempt to publish feedback on an uninitialized ServerGoalHandle")
            return
        self._server.publish_feedback(self._tracker.status, feedback)

    def set_cancel_requested(self) -> bool:
        """A cancel came for this goal: PENDING -> RECALLING, ACTIVE -> PREEMPTING; whether it moved."""
        GoalStatus = goal_status()
        if self._tracker is None or self._server is None:
            return False
        with self._server.lock:
            status = self._tracker.status
            following = {GoalStatus.PENDING: GoalStatus.RECALLING, GoalStatus.ACTIVE: GoalStatus.PREEMPTING}.get(status.status)
            if following is None:
                return False
            status.status = following
            self._server.publish_status()
            return True

    def _move(self, moves: dict[int, int], text: str, result: Message | None, target: str, allowed: str) -> None:
        if self._tracker is None or self._server is None:
            logerr("Attempt to set status on an uninitialized ServerGoalHandle")
            return
        with self._server.lock:
            status = self._tracker.status
            following = moves.get(status.status)
            if following is None:
                logerr("To transition to %s, the goal must be in %s, it is currently in state: %d", target, allowed, status.status)
                return
            status.status, status.text = following, text
            if following in (goal_status().ACTIVE, goal_status().PREEMPTING):
                self._server.publish_status()
            else:
                self._tracker.ended_at = time.monotonic()
                self._server.publish_result(status, result if result is not None else self._server.types.result())


class ActionServer:
    """Serves action ``ns`` (see the module docstring): ``goal_cb(handle)`` for each new goal,
    ``cancel_cb(handle)`` for each goal a cancel request moved."""

    def __init__(
        self, ns: str, ActionSpec: Any, goal_cb: Callable[[ServerGoalHandle], Any],
        cancel_cb: Callable[[ServerGoalHandle], Any] = lambda handle: None, auto_start: bool = True,
    ) -> None:  # fmt: skip
        self.types = spec_types(ActionSpec, "actionlib.ActionServer")
        self.ns = ns
        self.goal_callback = goal_cb
        self.cancel_callback = cancel_cb
        self.lock = threading.RLock()
        self._trackers: list[_Tracker] = []
        self._last_cancel = Time()
        self._started = False
        self._status_array = actionlib_messages().GoalStatusArray
        self.status_pub = Publisher(f"{ns}/status", self._status_array, latch=True, queue_size=_QUEUE_SIZE)
        self.result_pub = Publisher(f"{ns}/result", self.types.action_result, queue_size=_QUEUE_SIZE)
        self.feedback_pub = Publisher(f"{ns}/feedback", self.types.action_feedback, queue_size=_QUEUE_SIZE)
        self.goal_sub: Subscriber | None = None
        self.cancel_sub: Subscriber | None = None
        if auto_start:
            self.start()

    def start(self) -> None:
        """Take goals and cancels from now on, and publish the status 5 times a second."""
        with self.lock:
            if self._started:
                return
            self._started = True
        self.goal_sub = Subscriber(f"{self.ns}/goal", self.types.action_goal, self._goal_arrived)
        self.cancel_sub = Subscriber(f"{self.ns}/cancel", actionlib_messages().GoalID, self._cancel_arrived)
        threading.Thread(target=self._publish_status_loop, name=f"actionlib status {self.ns}", daemon=True).start()
        self.publish_status()

    # -- publishing ---------------------------------------------------------------------------

    def publish_status(self) -> None:
        """Publish every goal tracked (those ended more than 5 s ago are dropped first)."""
        with self.lock:
            now = time.monotonic()
            self._trackers = [t for t in self._trackers if t.ended_at is None or now - t.ended_at < _STATUS_LIST_TIMEOUT_S]
            statuses = [t.status.model_copy(deep=True) for t in self._trackers]
        array = self._status_array(status_list=statuses)
        array.header.stamp = Time.now()
        self.status_pub.publish(array)

    def publish_result(self, status: Any, result: Message) -> None:
        envelope: Any = self.types.action_result(status=status.model_copy(deep=True), result=result)
        envelope.header.stamp = Time.now()
        self.result_pub.publish(envelope)
        self.publish_status()

    def publish_feedback(self, status: Any, feedback: Message) -> None:
        envelope: Any = self.types.action_feedback(status=status.model_copy(deep=True), feedback=feedback)
        envelope.header.stamp = Time.now()
        self.feedback_pub.publish(envelope)

    def _publish_status_loop(self) -> None:
        while not process.wait(_STATUS_PERIOD_S):
            self.publish_status()

    # -- what clients send --------------------------------------------------------------------

    def _goal_arrived(self, envelope: Any) -> None:
        GoalStatus = goal_status()
        with self.lock:
            goal_id = envelope.goal_id
            for tracker in self._trackers:
                if tracker.status.goal_id.id == goal_id.id:
                    if tracker.status.status == GoalStatus.RECALLING:  # its cancel came first
                        tracker.status.status = GoalStatus.RECALLED
                        tracker.ended_at = time.monotonic()
                        self.publish_result(tracker.status, self.types.result())
                    return  # a goal seen before: nothing new
            if goal_id.stamp.to_nsec() == 0:
                goal_id.stamp = Time.now()
            tracker = _Tracker(GoalStatus(goal_id=goal_id, status=GoalStatus.PENDING), envelope)
            self._trackers.append(tracker)
            handle = ServerGoalHandle(tracker, self)
            if goal_id.stamp.to_nsec() <= self._last_cancel.to_nsec():
                handle.set_canceled(None, "This goal handle was canceled by the action server because its timestamp is before the timestamp of the last cancel request")
                return
            self.goal_callback(handle)

    def _cancel_arrived(self, goal_id: Any) -> None:
        GoalStatus = goal_status()
        with self.lock:
            stamp_ns = goal_id.stamp.to_nsec()
            everything = goal_id.id == "" and stamp_ns == 0
            found = False
            for tracker in list(self._trackers):
                this_one = goal_id.id == tracker.status.goal_id.id
                before = stamp_ns != 0 and tracker.status.goal_id.stamp.to_nsec() <= stamp_ns
                if not (everything or this_one or before):
                    continue
                found = found or this_one
                handle = ServerGoalHandle(tracker, self)
                if tracker.goal is not None and handle.set_cancel_requested():
                    self.cancel_callback(handle)
            if goal_id.id and not found:  # the goal may come later: it is recalled then
                tracker = _Tracker(GoalStatus(goal_id=goal_id, status=GoalStatus.RECALLING), None)
                tracker.ended_at = time.monotonic()
                self._trackers.append(tracker)
            if stamp_ns > self._last_cancel.to_nsec():
                self._last_cancel = Time.from_nsec(stamp_ns)
