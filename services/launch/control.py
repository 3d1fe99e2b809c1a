"""The launch as a node: ``/skydeck_launch`` serves ``/skydeck_launch/kill_node`` so that
``skydeck node kill NAME`` can ask the supervisor to stop one of its nodes for good, and what
that does to the launch (:func:`kill_launched`).

ROS's ``rosnode kill`` asks the node itself to shut down, and roslaunch then respawns it if
told to. Here the supervisor is asked instead, so it knows the death was wanted and does not
respawn the node. The node is started once the launch's core is up and stopped with the launch.
"""

from __future__ import annotations

import contextlib
from collections.abc import Awaitable, Callable, Mapping

from services.launch.launched import LaunchedNode
from services.runtime.http_client import HttpClient, HttpError
from services.runtime.node import Node
from services.runtime.settings import NodeSettings
from shared_models.skydeck_launch import KillNode, KillNodeRequest, KillNodeResponse

__all__ = ["KILL_SERVICE", "LAUNCH_NODE", "KillNode", "LaunchControl", "kill_launched"]

LAUNCH_NODE = "/skydeck_launch"
KILL_SERVICE = "/skydeck_launch/kill_node"


class LaunchControl(Node):
    """The supervisor's node; ``kill(name)`` gives the service's answer."""

    def __init__(self, kill: Callable[[str], Awaitable[KillNodeResponse]], settings: NodeSettings) -> None:
        super().__init__(LAUNCH_NODE, settings=settings)
        self._kill = kill
        self.create_service(KillNode, KILL_SERVICE, self._on_kill)

    async def _on_kill(self, request: KillNodeRequest) -> KillNodeResponse:
        return await self._kill(request.node)


async def kill_launched(
    node: str,
    children: Mapping[str, LaunchedNode],
    *,
    http: HttpClient | None,
    core_url: str,
    terminate: Callable[[LaunchedNode], Awaitable[None]],
) -> KillNodeResponse:
    """Stop the child of ``children`` running graph node ``node`` for good (it is marked so, and
    not respawned); the answer's ``reason`` says what was done or why not (its constants)."""
    child, in_graph = await _child_of_node(node, children, http, core_url)

    def refuse(reason: str, message: str) -> KillNodeResponse:
        return KillNodeResponse(success=False, reason=reason, message=message)

    if child is None and not in_graph:
        return refuse(KillNodeResponse.UNKNOWN_NODE, f"unknown node {node}: see `skydeck node list`")
    if child is None:
        return refuse(KillNodeResponse.NOT_LAUNCHED, f"{node} was not started by this launch: stop it where it was started")
    if child.plan.is_core:
        return refuse(KillNodeResponse.PROTECTED, f"{node} is the core, which `node kill` leaves: stop the whole launch with Ctrl-C")
    if not child.running or child.pid is None:
        return refuse(KillNodeResponse.NOT_RUNNING, f"{node} is not running ({child.state.value})")
    pid = child.pid
    child.kill_requested = True
    await terminate(child)
    return KillNodeResponse(
        success=True,
        reason=KillNodeResponse.KILLED,
        message=f"killed {node} (launch node {child.plan.name}, pid {pid}); not respawned",
    )


async def _child_of_node(
    node: str, children: Mapping[str, LaunchedNode], http: HttpClient | None, core_url: str
) -> tuple[LaunchedNode | None, bool]:
    """The child whose process registered ``node`` (matched by pid), else one named so; and
    whether the graph has ``node`` (if the core could be asked, else assumed; it matters only
    when no child is found)."""
    in_graph = True
    if http is not None:
        with contextlib.suppress(HttpError, ValueError):
            reply = await http.get(f"{core_url}/api/nodes{node}", timeout_s=2.0)
            in_graph = reply.status != 404
            if reply.status == 200:
                pid = reply.json().get("pid")
                for child in children.values():
                    if child.pid == pid and child.running:
                        return child, True
    return children.get(node.lstrip("/")), in_graph
