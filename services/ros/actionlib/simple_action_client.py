"""``actionlib.SimpleActionClient``: one goal at a time, as the ROS 1 course's clients send them.

    client = actionlib.SimpleActionClient('fibonacci', actionlib_tutorials.msg.FibonacciAction)
    client.wait_for_server()
    client.send_goal(actionlib_tutorials.msg.FibonacciGoal(order=20), feedback_cb=on_feedback)
    client.wait_for_result()
    result = client.get_result()

It publishes ``NAME/goal`` and ``NAME/cancel`` and follows ``NAME/status``, ``NAME/feedback`` and
``NAME/result`` (actionlib's topics and types, :mod:`.action_server`). A goal's ID is actionlib's
(``NODE-COUNT-SECONDS``). Callbacks run on the subscribers' threads, as rospy's do:
``active_cb()`` once the server works on the goal, ``feedback_cb(feedback)``, then
``done_cb(state, result)`` with its terminal ``GoalStatus`` when its result comes (``LOST`` if the
server forgets a goal it was working on). Timeouts are rospy Durations (or seconds) of wall time;
zero waits for ever.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from services.ros.actionlib.spec import GoalIdGenerator, goal_status, seconds, spec_types
from services.ros.rospy.core import process
from services.ros.rospy.log import logerr
from services.ros.rospy.rostime import Time
from services.ros.rospy.topics import Publisher, Subscriber
from services.runtime.actions.messages import actionlib_messages
from shared_models import Message

__all__ = ["SimpleActionClient", "SimpleGoalState"]

_SERVER_POLL_S = 0.01  # as actionlib's wait_for_server
_QUEUE_SIZE = 10


class SimpleGoalState:
    """Where the simple client's goal is: ``PENDING``, ``ACTIVE``, ``DONE``."""

    PENDING = 0
    ACTIVE = 1
    DONE = 2

    @staticmethod
    def to_string(state: int) -> str:
        return {0: "PENDING", 1: "ACTIVE", 2: "DONE"}.get(state, f"BUG-UNKNOWN-{state}")


class _Goal:
    """The goal being tracked and what is known of it."""

    def __init__(self, goal_id: Any, done_cb: Callable[..., Any] | None, active_cb: Callable[[], Any] | None,
                 feedback_cb: Callable[[Any], Any] | None) -> None:  # fmt: skip
        self.goal_id = goal_id
        self.status = goal_status().PENDING
        self.text = ""
        self.result: Message | None = None
        self.state = SimpleGoalState.PENDING
        self.seen = False  # in the server's status list at least once
        self.reported = False  # done_cb has returned: wait_for_result wakes only then, as in ROS
        self.done_cb, self.active_cb, self.feedback_cb = done_cb, active_cb, feedback_cb


class SimpleActionClient:
    """Sends goals to action ``ns`` one at a time (see the module docstring)."""

    def __init__(self, ns: str, ActionSpec: Any) -> None:
        self.types = spec_types(ActionSpec, "actionlib.SimpleActionClient")
        self.ns = ns
        self._ids = GoalIdGenerator()
        self._goal_id_type = actionlib_messages().GoalID
        self._done = threading.Condition()
        self._goal: _Goal | None = None
        self._status_seen = threading.Event()
        self.pub_goal = Publisher(f"{ns}/goal", self.types.action_goal, queue_size=_QUEUE_SIZE)
        self.pub_cancel = Publisher(f"{ns}/cancel", self._goal_id_type, queue_size=_QUEUE_SIZE)
        self._subscribers = [
            Subscriber(f"{ns}/status", actionlib_messages().GoalStatusArray, self._status_arrived, queue_size=1),
            Subscriber(f"{ns}/feedback", self.types.action_feedback, self._feedback_arrived),
            Subscriber(f"{ns}/result", self.types.action_result, self._result_arrived),
        ]

    @property
    def simple_state(self) -> int:
        goal = self._goal
        return SimpleGoalState.DONE if goal is None else goal.state

    # -- the server ---------------------------------------------------------------------------

    def wait_for_server(self, timeout: Any = 0.0) -> bool:
        """Wait until the server's status comes and its topics are linked both ways; False if
        ``timeout`` passes first."""
        limit = seconds(timeout, "wait_for_server")
        deadline = time.monotonic() + limit if limit > 0 else None
        while not process.is_shutdown():
            if self._server_ready():
                return True
            if deadline is not None and time.monotonic() >= deadline:
                return False
            process.wait(_SERVER_POLL_S)
        return False

    def _server_ready(self) -> bool:
        node = process.node
        if node is None or not self._status_seen.is_set():
            return False
        linked = all(node.is_linked(subscriber.name) for subscriber in self._subscribers)
        return linked and self.pub_goal.get_num_connections() > 0 and self.pub_cancel.get_num_connections() > 0

    # -- the goal -----------------------------------------------------------------------------

    def send_goal(
        self, goal: Message, done_cb: Callable[..., Any] | None = None, active_cb: Callable[[], Any] | None = None,
        feedback_cb: Callable[[Any], Any] | None = None,
    ) -> None:  # fmt: skip
        """Send ``goal`` (the action's Goal), forgetting the goal tracked before."""
        if not isinstance(goal, self.types.goal):
            raise TypeError(f"send_goal takes {self.types.goal.__name__} (the action's Goal), got {type(goal).__name__}")
        goal_id = self._ids.generate()
        envelope: Any = self.types.action_goal(goal_id=goal_id, goal=goal)
        envelope.header.stamp = goal_id.stamp
        with self._done:
            self._goal = _Goal(goal_id, done_cb, active_cb, feedback_cb)
        self.pub_goal.publish(envelope)

    def send_goal_and_wait(self, goal: Message, execute_timeout: Any = 0.0, preempt_timeout: Any = 0.0) -> int:
        """Send ``goal``, wait for its result (cancelling it after ``execute_timeout``, then
        waiting ``preempt_timeout``); its state."""
        self.send_goal(goal)
        if not self.wait_for_result(execute_timeout):
            self.cancel_goal()
            self.wait_for_result(preempt_timeout)
        return self.get_state()

    def wait_for_result(self, timeout: Any = 0.0) -> bool:
        """Wait until the goal is done; whether it is (False if ``timeout`` passed first)."""
        limit = seconds(timeout, "wait_for_result")
        if self._goal is None:
            logerr("Called wait_for_result when no goal exists")
            return False
        deadline = time.monotonic() + limit if limit > 0 else None
        goal = self._goal
        with self._done:
            while not process.is_shutdown() and not goal.reported and self._goal is goal:
                left = 0.1 if deadline is None else min(0.1, deadline - time.monotonic())
                if left <= 0:
                    break
                self._done.wait(left)
        return self.simple_state == SimpleGoalState.DONE

    def get_result(self) -> Message | None:
        """The goal's result (the action's Result), None before it comes."""
        if self._goal is None:
            logerr("Called get_result when no goal is running")
            return None
        return self._goal.result

    def get_state(self) -> int:
        """The goal's ``GoalStatus`` as the simple client sees it (RECALLING reads PENDING,
        PREEMPTING reads ACTIVE)."""
        GoalStatus = goal_status()
        if self._goal is None:
            logerr("Called get_state when no goal is running")
            return int(GoalStatus.LOST)
        status = self._goal.status
        return {GoalStatus.RECALLING: GoalStatus.PENDING, GoalStatus.PREEMPTING: GoalStatus.ACTIVE}.get(status, status)

    def get_goal_status_text(self) -> str:
        if self._goal is None:
            logerr("Called get_goal_status_text when no goal is running")
            return "ERROR: Called get_goal_status_text when no goal is running"
        return self._goal.text

    def cancel_goal(self) -> None:
        """Ask the server to cancel the goal."""
        if self._goal is not None:
            self.pub_cancel.publish(self._goal_id_type(stamp=Time(), id=self._goal.goal_id.id))

    def cancel_all_goals(self) -> None:
        """Ask the server to cancel every goal it has, from any client."""
        self.pub_cancel.publish(self._goal_id_type())

    def cancel_goals_at_and_before_time(self, time: Any) -> None:
        """Ask the server to cancel every goal stamped at or before ``time``."""
        self.pub_cancel.publish(self._goal_id_type(stamp=time, id=""))

    def stop_tracking_goal(self) -> None:
        """Forget the goal (its callbacks are not called any more)."""
        with self._done:
            self._goal = None

    # -- the server's topics (on the subscribers' threads) --------------------------------------

    def _status_arrived(self, array: Any) -> None:
        self._status_seen.set()
        calls: list[Callable[[], Any]] = []
        with self._done:
            goal = self._goal
            if goal is None or goal.state == SimpleGoalState.DONE:
                return
            line = next((s for s in array.status_list if s.goal_id.id == goal.goal_id.id), None)
            if line is None:
                if goal.seen and goal.status not in _terminal():
                    self._finish(goal, goal_status().LOST, "", None, calls)  # the server forgot it
            else:
                goal.seen = True
                goal.status, goal.text = line.status, line.text
                self._maybe_active(goal, calls)
        for call in calls:
            call()

    def _feedback_arrived(self, envelope: Any) -> None:
        goal = self._goal
        if goal is None or goal.state == SimpleGoalState.DONE or envelope.status.goal_id.id != goal.goal_id.id:
            return
        if goal.feedback_cb is not None:
            goal.feedback_cb(envelope.feedback)

    def _result_arrived(self, envelope: Any) -> None:
        calls: list[Callable[[], Any]] = []
        with self._done:
            goal = self._goal
            if goal is None or goal.state == SimpleGoalState.DONE or envelope.status.goal_id.id != goal.goal_id.id:
                return
            goal.status = envelope.status.status
            self._maybe_active(goal, calls)
            self._finish(goal, envelope.status.status, envelope.status.text, envelope.result, calls)
        for call in calls:
            call()

    def _maybe_active(self, goal: _Goal, calls: list[Callable[[], Any]]) -> None:
        GoalStatus = goal_status()
        worked_on = (GoalStatus.ACTIVE, GoalStatus.PREEMPTING, GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.PREEMPTED)
        if goal.state == SimpleGoalState.PENDING and goal.status in worked_on:
            goal.state = SimpleGoalState.ACTIVE
            if goal.active_cb is not None:
                calls.append(goal.active_cb)

    def _finish(self, goal: _Goal, status: int, text: str, result: Message | None, calls: list[Callable[[], Any]]) -> None:
        goal.status, goal.text, goal.result, goal.state = status, text, result, SimpleGoalState.DONE
        calls.append(lambda: self._report(goal, status, result))

    def _report(self, goal: _Goal, status: int, result: Message | None) -> None:
        # ROS's client runs done_cb before it wakes a waiter: a program's prints stay in order.
        try:
            if goal.done_cb is not None:
                goal.done_cb(status, result)
        finally:
            with self._done:
                goal.reported = True
                self._done.notify_all()


def _terminal() -> tuple[int, ...]:
    GoalStatus = goal_status()
    return (GoalStatus.PREEMPTED, GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.REJECTED, GoalStatus.RECALLED, GoalStatus.LOST)
