"""The registration session between a node and the core (``ws://CORE/api/session``).

One JSON object per text frame, told apart by ``op``. The node opens with ``register`` and
sends ``update`` whenever its publications, subscriptions or services change, plus ``stats``
once a second; the core answers ``registered`` (with the key it forwards calls with, or
``rejected``) and pushes ``publishers`` for
every topic the node subscribes to, at once and whenever that list changes. The session's
life is the node's life in the registry: when it drops, the node leaves the graph.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

__all__ = [
    "CoreFrame",
    "CoreFrameModel",
    "Entity",
    "ForeignNode",
    "NodeDescription",
    "NodeFrame",
    "PublisherAddress",
    "PublishersFrame",
    "RegisteredFrame",
    "RegisterFrame",
    "RejectedFrame",
    "StatsFrame",
    "UpdateFrame",
    "core_frames",
    "node_frames",
]


class _Frame(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Entity(_Frame):
    """A topic or service of a node, with its ROS type name."""

    name: str
    type: str
    latched: bool = False


class ForeignNode(_Frame):
    """A participant of another system that a node bridges to (a ROS 2 node seen over DDS by the
    ROS 2 bridge): listed in the graph, marked with its ``system``, never linked to."""

    name: str
    system: str
    publications: list[Entity] = []
    subscriptions: list[Entity] = []
    services: list[Entity] = []


class NodeDescription(_Frame):
    """What a node tells the core about itself."""

    name: str
    url: str
    pid: int
    # Set for a client of the core that the graph shows as a node (a rosbridge or Foxglove
    # connection: "rosbridge client 127.0.0.1:50312"); empty for a node.
    client: str = ""
    publications: list[Entity] = []
    subscriptions: list[Entity] = []
    services: list[Entity] = []
    # The definition files of the types its entities use that Skydeck does not ship (a
    # workspace's msg/srv/action), by the type each declares ("my_pkg/msg/Status": "int32 x\n"):
    # how the core, the dashboard, rosbridge, Foxglove and bags learn a node's own types.
    interfaces: dict[str, str] = {}
    # The other systems' participants this node bridges to; they leave the graph with it.
    foreign: list[ForeignNode] = []


class RegisterFrame(_Frame):
    op: Literal["register"] = "register"
    node: NodeDescription


class UpdateFrame(_Frame):
    op: Literal["update"] = "update"
    node: NodeDescription


class StatsFrame(_Frame):
    op: Literal["stats"] = "stats"
    # Messages published so far on each topic (cumulative: the core derives rates from deltas).
    published: dict[str, int]


class RegisteredFrame(_Frame):
    op: Literal["registered"] = "registered"
    # This registration's key: the core forwards the calls it admitted to the node with it (as
    # a bearer token), so a node with a token of its own accepts what the core's fences let
    # through (an instructor's call to a student's node). A secret: never logged.
    key: str = ""


class RejectedFrame(_Frame):
    op: Literal["rejected"] = "rejected"
    reason: str


class PublisherAddress(_Frame):
    node: str
    url: str


class PublishersFrame(_Frame):
    op: Literal["publishers"] = "publishers"
    topic: str
    publishers: list[PublisherAddress]


NodeFrame = Annotated[RegisterFrame | UpdateFrame | StatsFrame, Field(discriminator="op")]
CoreFrame = Annotated[RegisteredFrame | RejectedFrame | PublishersFrame, Field(discriminator="op")]

node_frames: TypeAdapter[RegisterFrame | UpdateFrame | StatsFrame] = TypeAdapter(NodeFrame)
CoreFrameModel = RegisteredFrame | RejectedFrame | PublishersFrame
"""Any frame the core sends a node."""

core_frames: TypeAdapter[RegisteredFrame | RejectedFrame | PublishersFrame] = TypeAdapter(CoreFrame)
