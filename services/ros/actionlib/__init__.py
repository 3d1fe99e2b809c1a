"""Skydeck's actionlib (ROS 1's actions): ``import actionlib`` in a file ``skydeck run`` runs.

    import actionlib
    from actionlib_tutorials.msg import FibonacciAction, FibonacciGoal

    server = actionlib.SimpleActionServer('fibonacci', FibonacciAction, execute_cb=execute, auto_start=False)
    server.start()

    client = actionlib.SimpleActionClient('fibonacci', FibonacciAction)
    client.wait_for_server()
    client.send_goal(FibonacciGoal(order=5))

Written on the rospy façade, as actionlib is written on rospy: its topics (``NAME/goal``,
``cancel``, ``status``, ``feedback``, ``result``) and types (``XActionGoal``...) are actionlib's,
so a rosbridge client's actionlib (roslibjs, roslibpy) talks to it. Its messages are
``actionlib.msg`` (the test actions) and each package's ``msg`` (``FibonacciAction``...).
"""

from __future__ import annotations

from typing import Any

from services.ros.actionlib.action_server import ActionServer, ServerGoalHandle
from services.ros.actionlib.simple_action_client import SimpleActionClient, SimpleGoalState
from services.ros.actionlib.simple_action_server import SimpleActionServer
from services.ros.actionlib.spec import goal_status

__all__ = [
    "ActionServer",
    "GoalStatus",
    "ServerGoalHandle",
    "SimpleActionClient",
    "SimpleActionServer",
    "SimpleGoalState",
    "get_name_of_constant",
]

_NOT_PROVIDED = frozenset({"ActionClient", "ClientGoalHandle", "CommState", "TerminalState", "GoalManager", "ActionException"})


def get_name_of_constant(C: type, n: int) -> str:
    """The name of the constant of class ``C`` whose value is ``n`` (``GoalStatus``, 3 -> ``SUCCEEDED``)."""
    for name, value in vars(C).items():
        if name.isupper() and value == n:
            return name
    return f"NO_SUCH_STATE_{n}"


def __getattr__(name: str) -> Any:
    if name == "GoalStatus":  # actionlib_msgs/GoalStatus, loaded on first use
        return goal_status()
    if name in _NOT_PROVIDED:
        from services.ros.errors import NotProvidedError, not_provided

        raise NotProvidedError(not_provided(f"`actionlib.{name}` (use SimpleActionClient)"))
    raise AttributeError(f"module 'actionlib' has no attribute {name!r}")
