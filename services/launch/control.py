"""The launch as a node: ``/skydeck_launch`` serves ``/skydeck_launch/kill_node`` so that
``skydeck node kill NAME`` can ask the supervisor to stop one of its nodes for good.

ROS's ``rosnode kill`` asks the node itself to shut down, and roslaunch then respawns it if
told to. Here the supervisor is asked instead, so it knows the death was wanted and does not
respawn the node. The node is started once the launch's core is up and stopped with the launch.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable

from services.runtime.node import Node
from services.runtime.settings import NodeSettings
from shared_models.skydeck_launch import KillNode, KillNodeRequest, KillNodeResponse

__all__ = ["KILL_SERVICE", "LAUNCH_NODE", "KillNode", "LaunchControl"]

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
