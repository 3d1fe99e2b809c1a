"""skydeck_launch: the launch supervisor's own service, ``/skydeck_launch/kill_node``.

A package of its own, in the catalogue like every other, so that the core (which never imports
the launcher) knows the type of a service the graph shows (``/api/interfaces``, ``/docs``).
"""

from __future__ import annotations

from typing import ClassVar

from shared_models._message import Bool, Message, ServiceType, String

__all__ = ["KillNode", "KillNodeRequest", "KillNodeResponse"]


class KillNodeRequest(Message):
    """Which node to stop: its name in the graph (``/sim``)."""

    __ros_type__ = "skydeck_launch/srv/KillNode_Request"

    node: String = ""


class KillNodeResponse(Message):
    """Whether the supervisor stopped it, what it did or why not (``message``, for people), and
    ``reason``, one of the constants, for programs (``skydeck node kill`` picks its fallback by it)."""

    __ros_type__ = "skydeck_launch/srv/KillNode_Response"
    __ros_constants__ = ("KILLED", "UNKNOWN_NODE", "NOT_LAUNCHED", "PROTECTED", "NOT_RUNNING")

    KILLED: ClassVar[String] = "killed"  # stopped; not respawned
    UNKNOWN_NODE: ClassVar[String] = "unknown_node"  # no node of that name in the graph or the launch
    NOT_LAUNCHED: ClassVar[String] = "not_launched"  # in the graph, but not started by this launch
    PROTECTED: ClassVar[String] = "protected"  # the core: stop the whole launch instead
    NOT_RUNNING: ClassVar[String] = "not_running"  # a node of the launch that is not running now

    success: Bool = False
    message: String = ""
    reason: String = ""


class KillNode(ServiceType):
    """Stop a node of this launch on purpose: it is not respawned."""

    __ros_type__ = "skydeck_launch/srv/KillNode"
    Request = KillNodeRequest
    Response = KillNodeResponse
