"""ROS 2 actions on Skydeck's services and topics, with ROS 2's names, types and rules.

    names.py      an action's services and topics (``NAME/_action/send_goal``...), found in a graph
    goals.py      goal IDs, statuses and ROS 2's goal state machine
    server.py     ActionServer: goals accepted, cancelled, executed, their results kept and expired
    client.py     ActionClient: goals sent, their feedback and status followed, results asked for
    transport.py  how a client reaches the graph (a node's calls and subscriptions)
    messages.py   the types every action shares (action_msgs, unique_identifier_msgs; actionlib_msgs)

The rclpy façade (``rclpy.action``), ``skydeck action`` and rosbridge's action ops build on
these; see docs/ros.md, "Actions". The exports load lazily: listing actions needs only ``names``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from shared_models.lazy import lazy_exports

if TYPE_CHECKING:
    from services.runtime.actions.client import ActionClient, ClientGoal
    from services.runtime.actions.goals import (
        STATUS_NAMES,
        GoalEvent,
        GoalStatusCode,
        GoalTransitionError,
        goal_id_text,
        new_goal_id,
    )
    from services.runtime.actions.names import ActionNames, actions_in_graph
    from services.runtime.actions.server import ActionServer, ServerGoal
    from services.runtime.actions.transport import ActionTransport, NodeTransport

__all__ = [
    "ActionClient",
    "ActionNames",
    "ActionServer",
    "ActionTransport",
    "ClientGoal",
    "GoalEvent",
    "GoalStatusCode",
    "GoalTransitionError",
    "NodeTransport",
    "STATUS_NAMES",
    "ServerGoal",
    "actions_in_graph",
    "goal_id_text",
    "new_goal_id",
]

_HOMES = {
    "ActionClient": "services.runtime.actions.client",
    "ActionNames": "services.runtime.actions.names",
    "ActionServer": "services.runtime.actions.server",
    "ActionTransport": "services.runtime.actions.transport",
    "ClientGoal": "services.runtime.actions.client",
    "GoalEvent": "services.runtime.actions.goals",
    "GoalStatusCode": "services.runtime.actions.goals",
    "GoalTransitionError": "services.runtime.actions.goals",
    "NodeTransport": "services.runtime.actions.transport",
    "STATUS_NAMES": "services.runtime.actions.goals",
    "ServerGoal": "services.runtime.actions.server",
    "actions_in_graph": "services.runtime.actions.names",
    "goal_id_text": "services.runtime.actions.goals",
    "new_goal_id": "services.runtime.actions.goals",
}

__getattr__ = lazy_exports(__name__, _HOMES)
