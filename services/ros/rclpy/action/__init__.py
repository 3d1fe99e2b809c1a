"""``rclpy.action``: ROS 2 actions (``ActionServer``, ``ActionClient``), on Skydeck's SDK.

    from rclpy.action import ActionServer, ActionClient, CancelResponse, GoalResponse

The names, types and rules are ROS 2's (:mod:`services.runtime.actions`); where it differs from
rclpy, and why, is in docs/ros.md ("Actions").
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from services.ros.rclpy.action.client import ActionClient, ClientGoalHandle
from services.ros.rclpy.action.server import (
    ActionServer,
    CancelResponse,
    GoalEvent,
    GoalResponse,
    ServerGoalHandle,
)
from services.runtime.actions.names import actions_in_graph

if TYPE_CHECKING:
    from services.ros.rclpy.node import Node

__all__ = [
    "ActionClient",
    "ActionServer",
    "CancelResponse",
    "ClientGoalHandle",
    "GoalEvent",
    "GoalResponse",
    "ServerGoalHandle",
    "get_action_names_and_types",
]


def get_action_names_and_types(node: Node) -> list[tuple[str, list[str]]]:
    """Every action in the graph and its type, as rclpy's (``[('/fibonacci', ['pkg/action/X'])]``)."""
    return [(action.name, [action.type]) for action in actions_in_graph(node._graph()).values()]


def __getattr__(name: str) -> Any:
    from services.ros.errors import NotProvidedError, not_provided

    if name in ("get_action_client_names_and_types_by_node", "get_action_server_names_and_types_by_node"):
        raise NotProvidedError(not_provided(f"rclpy.action.{name}"))
    raise AttributeError(f"module 'rclpy.action' has no attribute {name!r}")
