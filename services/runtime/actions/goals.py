"""A ROS 2 action goal's life: its ID, its statuses and the events that move it between them.

The state machine is ROS 2's (rcl_action's ``goal_state_machine``), status values those of
``action_msgs/msg/GoalStatus``::

    ACCEPTED  --EXECUTE-->      EXECUTING
    ACCEPTED  --CANCEL_GOAL-->  CANCELING
    EXECUTING --CANCEL_GOAL-->  CANCELING
    EXECUTING --SUCCEED/ABORT-->              SUCCEEDED / ABORTED
    CANCELING --SUCCEED/ABORT/CANCELED-->     SUCCEEDED / ABORTED / CANCELED

Anything else raises :class:`GoalTransitionError` with rcl's words.
"""

from __future__ import annotations

import uuid
from enum import Enum

from shared_models.errors import SkydeckError

__all__ = [
    "ACTIVE_STATUSES",
    "STATUS_NAMES",
    "TERMINAL_STATUSES",
    "GoalEvent",
    "GoalStatusCode",
    "GoalTransitionError",
    "goal_id_text",
    "new_goal_id",
    "next_status",
]


class GoalStatusCode:
    """``action_msgs/msg/GoalStatus``'s values."""

    UNKNOWN = 0
    ACCEPTED = 1
    EXECUTING = 2
    CANCELING = 3
    SUCCEEDED = 4
    CANCELED = 5
    ABORTED = 6


STATUS_NAMES = {
    GoalStatusCode.UNKNOWN: "UNKNOWN",
    GoalStatusCode.ACCEPTED: "ACCEPTED",
    GoalStatusCode.EXECUTING: "EXECUTING",
    GoalStatusCode.CANCELING: "CANCELING",
    GoalStatusCode.SUCCEEDED: "SUCCEEDED",
    GoalStatusCode.CANCELED: "CANCELED",
    GoalStatusCode.ABORTED: "ABORTED",
}
ACTIVE_STATUSES = frozenset({GoalStatusCode.ACCEPTED, GoalStatusCode.EXECUTING, GoalStatusCode.CANCELING})
TERMINAL_STATUSES = frozenset({GoalStatusCode.SUCCEEDED, GoalStatusCode.CANCELED, GoalStatusCode.ABORTED})


class GoalEvent(Enum):
    """What moves a goal (rclpy's ``GoalEvent``)."""

    EXECUTE = 1
    CANCEL_GOAL = 2
    SUCCEED = 3
    ABORT = 4
    CANCELED = 5


class GoalTransitionError(SkydeckError):
    """A goal was moved in a way ROS 2's goal state machine forbids (``canceled()`` on a goal
    nobody asked to cancel, ``succeed()`` twice)."""


_TRANSITIONS = {
    (GoalStatusCode.ACCEPTED, GoalEvent.EXECUTE): GoalStatusCode.EXECUTING,
    (GoalStatusCode.ACCEPTED, GoalEvent.CANCEL_GOAL): GoalStatusCode.CANCELING,
    (GoalStatusCode.EXECUTING, GoalEvent.CANCEL_GOAL): GoalStatusCode.CANCELING,
    (GoalStatusCode.EXECUTING, GoalEvent.SUCCEED): GoalStatusCode.SUCCEEDED,
    (GoalStatusCode.EXECUTING, GoalEvent.ABORT): GoalStatusCode.ABORTED,
    (GoalStatusCode.CANCELING, GoalEvent.SUCCEED): GoalStatusCode.SUCCEEDED,
    (GoalStatusCode.CANCELING, GoalEvent.ABORT): GoalStatusCode.ABORTED,
    (GoalStatusCode.CANCELING, GoalEvent.CANCELED): GoalStatusCode.CANCELED,
}


def next_status(status: int, event: GoalEvent) -> int:
    """The status ``event`` moves a goal in ``status`` to; GoalTransitionError if it may not."""
    following = _TRANSITIONS.get((status, event))
    if following is None:
        raise GoalTransitionError(
            f"goal_handle attempted invalid transition from state {STATUS_NAMES.get(status, status)} "
            f"with event {event.name}"
        )
    return following


def new_goal_id() -> bytes:
    """A random goal ID (a UUID's 16 bytes), as rclpy makes one."""
    return uuid.uuid4().bytes


def goal_id_text(goal_id: bytes) -> str:
    """A goal ID as ``ros2 action`` prints it: 32 hex digits."""
    return goal_id.hex()
