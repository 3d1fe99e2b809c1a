"""``actionlib.SimpleActionServer``: one goal at a time, as the ROS 1 course writes its servers.

    class FibonacciAction:
        def __init__(self, name):
            self._as = actionlib.SimpleActionServer(name, FibonacciAction, execute_cb=self.execute_cb,
                                                    auto_start=False)
            self._as.start()

        def execute_cb(self, goal):
            for i in range(1, goal.order):
                if self._as.is_preempt_requested():
                    self._as.set_preempted()
                    return
                ...
                self._as.publish_feedback(self._feedback)
                r.sleep()
            self._as.set_succeeded(self._result)

With ``execute_cb``, goals run one after another on a thread of the server's own; a new goal
preempts the running one (``is_preempt_requested()`` turns true, and it is cancelled when the
new one is accepted). Without it, the program calls ``register_goal_callback`` and
``accept_new_goal()`` itself (and ``register_preempt_callback``). The rules are actionlib's: a
goal older than the current or the waiting one is cancelled on arrival, a waiting goal is
cancelled by a newer one, and an execute callback that returns without ending its goal has it
aborted, with actionlib's warning.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from services.ros.actionlib.action_server import ActionServer, ServerGoalHandle
from services.ros.actionlib.spec import goal_status
from services.ros.rospy.core import process, report
from services.ros.rospy.log import logerr, logwarn
from shared_models import Message

__all__ = ["SimpleActionServer"]

_LOOP_PERIOD_S = 0.1
_REPLACED = "This goal was canceled because another goal was received by the simple action server"


class SimpleActionServer:
    """A single-goal action server (see the module docstring)."""

    def __init__(
        self, name: str, ActionSpec: Any, execute_cb: Callable[[Message], Any] | None = None, auto_start: bool = True
    ) -> None:
        if execute_cb is not None and not callable(execute_cb):
            raise TypeError(f"SimpleActionServer's execute_cb must be a function, got {execute_cb!r}")
        self.execute_callback = execute_cb
        self.goal_callback: Callable[[], Any] | None = None
        self.preempt_callback: Callable[[], Any] | None = None
        self.current_goal = ServerGoalHandle()
        self.next_goal = ServerGoalHandle()
        self.new_goal = False
        self.preempt_request = False
        self.new_goal_preempt_request = False
        self.action_server = ActionServer(name, ActionSpec, self._goal_arrived, self._preempt_arrived, auto_start=False)
        self.lock = self.action_server.lock  # one lock: the server's callbacks hold it already
        self.execute_condition = threading.Condition(self.lock)
        if execute_cb is not None:
            threading.Thread(target=self._execute_loop, name=f"actionlib execute {name}", daemon=True).start()
        if auto_start:
            self.start()

    def start(self) -> None:
        self.action_server.start()

    # -- the goal -----------------------------------------------------------------------------

    def accept_new_goal(self) -> Message | None:
        """Make the waiting goal the current one (cancelling a current one still active) and
        return it; None (with actionlib's error) if none waits."""
        with self.lock:
            if not self.new_goal or self.next_goal.get_goal() is None:
                logerr("Attempting to accept the next goal when a new goal is not available")
                return None
            if self.is_active() and self.current_goal.get_goal() is not None and self.current_goal != self.next_goal:
                self.current_goal.set_canceled(None, _REPLACED)
            self.current_goal, self.new_goal = self.next_goal, False
            self.preempt_request, self.new_goal_preempt_request = self.new_goal_preempt_request, False
            self.current_goal.set_accepted("This goal has been accepted by the simple action server")
            return self.current_goal.get_goal()

    def is_new_goal_available(self) -> bool:
        return self.new_goal

    def is_preempt_requested(self) -> bool:
        """Whether a cancel, or a newer goal, asks the current goal to stop."""
        return self.preempt_request

    def is_active(self) -> bool:
        """Whether the current goal is being worked on (ACTIVE or PREEMPTING)."""
        if self.current_goal.get_goal() is None:
            return False
        GoalStatus = goal_status()
        return self.current_goal.get_goal_status().status in (GoalStatus.ACTIVE, GoalStatus.PREEMPTING)

    def set_succeeded(self, result: Message | None = None, text: str = "") -> None:
        with self.lock:
            self.current_goal.set_succeeded(result if result is not None else self.get_default_result(), text)

    def set_aborted(self, result: Message | None = None, text: str = "") -> None:
        with self.lock:
            self.current_goal.set_aborted(result if result is not None else self.get_default_result(), text)

    def set_preempted(self, result: Message | None = None, text: str = "") -> None:
        with self.lock:
            self.current_goal.set_canceled(result if result is not None else self.get_default_result(), text)

    def publish_feedback(self, feedback: Message) -> None:
        self.current_goal.publish_feedback(feedback)

    def get_default_result(self) -> Message:
        return self.action_server.types.result()

    def register_goal_callback(self, cb: Callable[[], Any]) -> None:
        if self.execute_callback is not None:
            logwarn("Cannot call SimpleActionServer.register_goal_callback() because an executeCallback exists. Not going to register it.")
            return
        self.goal_callback = cb

    def register_preempt_callback(self, cb: Callable[[], Any]) -> None:
        self.preempt_callback = cb

    # -- the action server's callbacks (under the lock) -----------------------------------------

    def _goal_arrived(self, goal: ServerGoalHandle) -> None:
        stamp = goal.get_goal_id().stamp.to_nsec()
        newer_than_current = self.current_goal.get_goal() is None or stamp >= self.current_goal.get_goal_id().stamp.to_nsec()
        newer_than_next = self.next_goal.get_goal() is None or stamp >= self.next_goal.get_goal_id().stamp.to_nsec()
        if not (newer_than_current and newer_than_next):
            goal.set_canceled(None, _REPLACED)
            return
        if self.next_goal.get_goal() is not None and (self.current_goal.get_goal() is None or self.next_goal != self.current_goal):
            self.next_goal.set_canceled(None, _REPLACED)
        self.next_goal, self.new_goal, self.new_goal_preempt_request = goal, True, False
        if self.is_active():
            self.preempt_request = True
            if self.preempt_callback is not None:
                self.preempt_callback()
        if self.goal_callback is not None:
            self.goal_callback()
        self.execute_condition.notify()

    def _preempt_arrived(self, preempt: ServerGoalHandle) -> None:
        if preempt == self.current_goal:
            self.preempt_request = True
            if self.preempt_callback is not None:
                self.preempt_callback()
        elif preempt == self.next_goal:
            self.new_goal_preempt_request = True

    # -- execute_cb's thread --------------------------------------------------------------------

    def _execute_loop(self) -> None:
        while not process.is_shutdown():
            if self.is_active():
                logerr("Should never reach this code with an active goal")
                return
            if self.is_new_goal_available():
                goal = self.accept_new_goal()
                if goal is not None and self.execute_callback is not None:
                    self._execute(goal, self.execute_callback)
                continue
            with self.execute_condition:
                if not self.new_goal:
                    self.execute_condition.wait(_LOOP_PERIOD_S)

    def _execute(self, goal: Message, execute_callback: Callable[[Message], Any]) -> None:
        try:
            execute_callback(goal)
        except Exception as error:
            report(error, "the execute callback of the simple action server")
            self.set_aborted(None, f"Exception in execute callback: {error}")
            return
        if self.is_active():
            logwarn(
                "Your executeCallback did not set the goal to a terminal status.  This is a bug in your "
                "ActionServer implementation. Fix your code!  For now, the ActionServer will set this goal to aborted"
            )
            self.set_aborted(None, "This goal was aborted by the simple action server. The user should have set a terminal status on this goal and did not")
