"""``skydeck action list | info | send_goal`` (ros2 action).

An action is found in the graph by its parts (``NAME/_action/send_goal``...). ``send_goal`` runs
a node of its own, ``action_send_goal_PID``, as ``ros2 action send_goal`` does: it waits for a
server, sends the goal, prints its feedback (``--feedback``) and its result, and on Ctrl-C
cancels the goal before it goes.
"""

from __future__ import annotations

import argparse
import asyncio
import os
from typing import Any

from services.cli.arguments import add_noun, add_verb, known_type_of, ros_name
from services.cli.core_client import get_json, node_settings
from services.cli.errors import CliError
from services.cli.formatting import message_from, to_yaml
from services.runtime.actions.names import ActionInGraph, actions_in_graph

__all__ = ["add_parser"]

_CORE_NODE = "/skydeck_core"  # reads feedback for its own clients (the dashboard), who are no action clients


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    verbs = add_noun(subparsers, "action", "list, inspect and send goals to actions")

    p = add_verb(verbs, "list", _list, "list the actions of the running system")
    p.add_argument("-t", "--show-types", action="store_true", help="show each action's type")
    p.add_argument("-a", "--all", action="store_true", help="also Skydeck's own (tf2_web_republisher's, for rosbridge clients)")

    p = add_verb(verbs, "info", _info, "the servers and clients of an action")
    p.add_argument("action", help="e.g. /fibonacci")

    p = add_verb(verbs, "send_goal", _send_goal, "send a goal and wait for its result (GOAL as YAML or JSON)")
    p.add_argument("action", help="e.g. /fibonacci")
    p.add_argument("type", help="e.g. example_interfaces/action/Fibonacci")
    p.add_argument("goal", nargs="?", default="{}", help='e.g. "{order: 5}"')
    p.add_argument("-f", "--feedback", action="store_true", help="print the goal's feedback as it comes")


def _actions() -> dict[str, ActionInGraph]:
    return actions_in_graph(get_json("/api/graph"))


def _list(args: argparse.Namespace) -> int:
    from services.runtime.service_groups import SYSTEM_NODES

    for name, action in _actions().items():
        if not args.all and action.servers and set(action.servers) <= SYSTEM_NODES:
            continue  # as `service list` leaves Skydeck's own services to --all
        print(name + (f" [{action.type}]" if args.show_types else ""))
    return 0


def _info(args: argparse.Namespace) -> int:
    name = ros_name(args.action)
    action = _actions().get(name)
    if action is None:
        raise CliError(f"unknown action {name}: see `skydeck action list`")
    clients = [node for node in action.clients if node != _CORE_NODE]
    print(f"Action: {name}")
    print(f"Action clients: {len(clients)}")
    for node in clients:
        print(f"    {node}")
    print(f"Action servers: {len(action.servers)}")
    for node in action.servers:
        print(f"    {node}")
    return 0


def _send_goal(args: argparse.Namespace) -> int:
    from shared_models import ActionType

    name = ros_name(args.action)
    action_type = known_type_of(args.type, ActionType, "is not an action type: see `skydeck interface list -a`")
    serving = _actions().get(name)
    if serving is not None and serving.type and serving.type != action_type.__ros_type__:
        raise CliError(f"{name} is an action of type {serving.type}, not {action_type.__ros_type__}")
    goal = message_from(args.goal, action_type.Goal)
    try:
        asyncio.run(_run_goal(name, action_type, goal, feedback=args.feedback))
    except KeyboardInterrupt:
        return 130
    return 0


async def _run_goal(name: str, action_type: Any, goal: Any, *, feedback: bool) -> None:
    from services.runtime.actions import STATUS_NAMES, ActionClient, NodeTransport, goal_id_text
    from services.runtime.node import Node

    node = Node(f"action_send_goal_{os.getpid()}", settings=node_settings(), start_parameter_services=False)
    await node.start()
    client = ActionClient(NodeTransport(node), action_type, name)
    sent = None
    try:
        print("Waiting for an action server to become available...", flush=True)
        await client.wait_for_server()
        print(f"Sending goal:\n     {_yaml(goal)}\n", flush=True)
        on_feedback = (lambda message: print(f"Feedback:\n    {_yaml(message.feedback)}\n", flush=True)) if feedback else None
        sent = await client.send_goal(goal, on_feedback=on_feedback)
        if not sent.accepted:
            print("Goal was rejected.", flush=True)
            return
        print(f"Goal accepted with ID: {goal_id_text(sent.goal_id)}\n", flush=True)
        response = await client.get_result(sent)
        sent = None  # ended: nothing to cancel
        print(f"Result:\n    {_yaml(response.result)}\n", flush=True)
        print(f"Goal finished with status: {STATUS_NAMES.get(response.status, 'UNKNOWN')}", flush=True)
    except asyncio.CancelledError:  # Ctrl-C: the goal is not left running
        if sent is not None and sent.accepted:
            print("Canceling goal...", flush=True)
            await client.cancel(sent)
            print("Goal canceled.", flush=True)
        raise
    finally:
        client.close()
        await node.stop()


def _yaml(message: Any) -> str:
    return to_yaml(message.model_dump(mode="json")) if type(message).model_fields else "{}"
