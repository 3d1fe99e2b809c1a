"""What actionlib reads from an action spec (``FibonacciAction``), and what it shares: goal IDs,
the status constants, timeouts.

An action spec is the ``XAction`` message ROS 1 generates (``action_goal``, ``action_result``,
``action_feedback``); its fields' types are the envelopes on the wire (``XActionGoal``...), and
each envelope's last field is the user's part (``XGoal``...).
"""

from __future__ import annotations

import itertools
import threading
from dataclasses import dataclass
from typing import Any

from services.ros.rospy.core import get_name
from services.ros.rospy.rostime import Time
from services.runtime.actions.messages import actionlib_messages
from shared_models import Message
from shared_models.builtin_interfaces import Duration as DurationMsg

__all__ = ["ActionSpecTypes", "GoalIdGenerator", "goal_status", "seconds", "spec_types"]


def goal_status() -> Any:
    """``actionlib_msgs/GoalStatus``: its constants (PENDING ... LOST) and the message."""
    return actionlib_messages().GoalStatus


@dataclass(frozen=True)
class ActionSpecTypes:
    """The message types of one action spec."""

    action_goal: type[Message]
    action_result: type[Message]
    action_feedback: type[Message]
    goal: type[Message]
    result: type[Message]
    feedback: type[Message]


def _field_type(message: type[Message], field: str, what: str) -> type[Message]:
    info = message.model_fields.get(field)
    annotation = info.annotation if info is not None else None
    if not (isinstance(annotation, type) and issubclass(annotation, Message)):
        raise TypeError(f"{what} needs an action spec such as actionlib_tutorials.msg.FibonacciAction, got {message!r}")
    return annotation


def spec_types(action_spec: Any, what: str) -> ActionSpecTypes:
    """The types of ``action_spec`` (``FibonacciAction``); TypeError naming ``what`` if it is none."""
    if not (isinstance(action_spec, type) and issubclass(action_spec, Message)):
        raise TypeError(f"{what} needs an action spec such as actionlib_tutorials.msg.FibonacciAction, got {action_spec!r}")
    action_goal = _field_type(action_spec, "action_goal", what)
    action_result = _field_type(action_spec, "action_result", what)
    action_feedback = _field_type(action_spec, "action_feedback", what)
    return ActionSpecTypes(
        action_goal, action_result, action_feedback,
        _field_type(action_goal, "goal", what), _field_type(action_result, "result", what),
        _field_type(action_feedback, "feedback", what),
    )  # fmt: skip


class GoalIdGenerator:
    """Goal IDs as actionlib makes them: ``NODE-COUNT-SECONDS`` (``/fibonacci_client-1-12.345``),
    unique across the graph's clients."""

    _counter = itertools.count(1)
    _lock = threading.Lock()

    def generate(self) -> Any:
        """A new ``actionlib_msgs/GoalID``, stamped now."""
        with self._lock:
            count = next(self._counter)
        now = Time.now()
        return actionlib_messages().GoalID(stamp=now, id=f"{get_name()}-{count}-{now.to_sec():.3f}")


def seconds(timeout: Any, what: str) -> float:
    """A timeout given as rospy gives one (a Duration, or seconds) in seconds; 0 is for ever."""
    if isinstance(timeout, DurationMsg):
        return timeout.to_sec()
    if isinstance(timeout, int | float) and not isinstance(timeout, bool):
        return float(timeout)
    raise TypeError(f"{what} takes a rospy.Duration (or seconds), got {timeout!r}")
