"""skydeck_launch: the launch supervisor's own service, ``/skydeck_launch/kill_node``.

A package of its own, in the catalogue like every other, so that the core (which never imports
the launcher) knows the type of a service the graph shows (``/api/interfaces``, ``/docs``).
"""

from __future__ import annotations

from shared_models._message import Bool, Message, ServiceType, String

__all__ = ["KillNode", "KillNodeRequest", "KillNodeResponse"]


class KillNodeRequest(Message):
    """Which node to stop: its name in the graph (``/sim``)."""

    __ros_type__ = "skydeck_launch/srv/KillNode_Request"

    node: String = ""


class KillNodeResponse(Message):
    """Whether the supervisor stopped it, and what it did or why not."""

    __ros_type__ = "skydeck_launch/srv/KillNode_Response"

    success: Bool = False
    message: String = ""


class KillNode(ServiceType):
    """Stop a node of this launch on purpose: it is not respawned."""

    __ros_type__ = "skydeck_launch/srv/KillNode"
    Request = KillNodeRequest
    Response = KillNodeResponse
