"""Where a ROS 2 action lives in the graph: three services and two topics under its name.

    /fibonacci/_action/send_goal     service  example_interfaces/action/Fibonacci_SendGoal
    /fibonacci/_action/cancel_goal   service  action_msgs/srv/CancelGoal
    /fibonacci/_action/get_result    service  example_interfaces/action/Fibonacci_GetResult
    /fibonacci/_action/feedback      topic    example_interfaces/action/Fibonacci_FeedbackMessage
    /fibonacci/_action/status        topic    action_msgs/msg/GoalStatusArray (latched)

An action is recognised in a graph by those parts, as ``ros2 action list`` recognises it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["ACTION_INFIX", "ActionInGraph", "ActionNames", "actions_in_graph"]

ACTION_INFIX = "/_action/"
_SEND_GOAL_SUFFIX = "_SendGoal"


@dataclass(frozen=True)
class ActionNames:
    """The names of an action's services and topics; ``name`` is resolved (``/fibonacci``)."""

    name: str

    @property
    def send_goal(self) -> str:
        return f"{self.name}{ACTION_INFIX}send_goal"

    @property
    def cancel_goal(self) -> str:
        return f"{self.name}{ACTION_INFIX}cancel_goal"

    @property
    def get_result(self) -> str:
        return f"{self.name}{ACTION_INFIX}get_result"

    @property
    def feedback(self) -> str:
        return f"{self.name}{ACTION_INFIX}feedback"

    @property
    def status(self) -> str:
        return f"{self.name}{ACTION_INFIX}status"


@dataclass
class ActionInGraph:
    """An action as the graph shows it: its type, the nodes serving it and those using it."""

    name: str
    type: str = ""
    servers: list[str] = field(default_factory=list)
    clients: list[str] = field(default_factory=list)


def _action_of(name: str) -> tuple[str, str] | None:
    base, infix, part = name.rpartition(ACTION_INFIX)
    if not infix or not base or "/" in part:
        return None
    return base, part


def actions_in_graph(graph: dict[str, Any]) -> dict[str, ActionInGraph]:
    """The actions of a graph (``/api/graph``), by name: an action server serves
    ``NAME/_action/send_goal``; its clients are the nodes subscribed to its feedback."""
    found: dict[str, ActionInGraph] = {}
    for service in graph.get("services", []):
        parts = _action_of(service["name"])
        if parts is None or parts[1] != "send_goal":
            continue
        action = found.setdefault(parts[0], ActionInGraph(parts[0]))
        type_name = service.get("type", "")
        if type_name.endswith(_SEND_GOAL_SUFFIX):
            action.type = type_name[: -len(_SEND_GOAL_SUFFIX)]
        node = service.get("node")
        if node and node not in action.servers:
            action.servers.append(node)
    for topic in graph.get("topics", []):
        parts = _action_of(topic["name"])
        if parts is None or parts[1] != "feedback" or parts[0] not in found:
            continue
        for node in topic.get("subscribers", []):
            if node not in found[parts[0]].clients:
                found[parts[0]].clients.append(node)
    return dict(sorted(found.items()))
