"""The types every ROS 2 action shares (``action_msgs``, ``unique_identifier_msgs``), loaded from
their definition files on first use; ROS 1's (``actionlib_msgs``) for the actionlib façade."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

from shared_models import get_interface

__all__ = ["ActionMessages", "ActionlibMessages", "action_messages", "actionlib_messages"]


@dataclass(frozen=True)
class ActionMessages:
    """ROS 2's: their fields are read by name, so they are typed loosely here."""

    UUID: Any
    GoalInfo: Any
    GoalStatus: Any
    GoalStatusArray: Any
    CancelGoal: Any


@dataclass(frozen=True)
class ActionlibMessages:
    """ROS 1's."""

    GoalID: Any
    GoalStatus: Any
    GoalStatusArray: Any


@functools.cache
def action_messages() -> ActionMessages:
    return ActionMessages(
        UUID=get_interface("unique_identifier_msgs/msg/UUID"),
        GoalInfo=get_interface("action_msgs/msg/GoalInfo"),
        GoalStatus=get_interface("action_msgs/msg/GoalStatus"),
        GoalStatusArray=get_interface("action_msgs/msg/GoalStatusArray"),
        CancelGoal=get_interface("action_msgs/srv/CancelGoal"),
    )


@functools.cache
def actionlib_messages() -> ActionlibMessages:
    return ActionlibMessages(
        GoalID=get_interface("actionlib_msgs/msg/GoalID"),
        GoalStatus=get_interface("actionlib_msgs/msg/GoalStatus"),
        GoalStatusArray=get_interface("actionlib_msgs/msg/GoalStatusArray"),
    )
