"""ros_workshop: the workshop's own types (the fly command, the AI's and the controller's state,
the simulator's world) and the reasons control gives when it refuses a command.

A refusal (``success: false``) names its reason as a tag at the start of its message,
``"[already_airborne] Seems like the drone is already flying!"``: the one place where the
workshop's services say *why* in a form a program reads. It works for every service type,
``std_srvs/Trigger`` included, whose fields cannot change.

    >>> refusal_message(Refusal.SAME_TARGET, "Already flying to (5, 3).")
    '[same_target] Already flying to (5, 3).'
    >>> refusal_reason('[same_target] Already flying to (5, 3).')
    <Refusal.SAME_TARGET: 'same_target'>
"""

from __future__ import annotations

import re
from enum import StrEnum
from typing import Annotated, Literal

from pydantic import Field

from shared_models._message import (
    Bool,
    Float32,
    Float64,
    Int32,
    Message,
    RosPrimitive,
    ServiceType,
    String,
    UInt32,
)
from shared_models.geometry_msgs import Point
from shared_models.std_msgs import Header

__all__ = [
    "AiStatus",
    "ControlState",
    "FlyCommand",
    "FlyCommandRequest",
    "FlyCommandResponse",
    "Refusal",
    "SimWorld",
    "refusal_message",
    "refusal_reason",
]


class Refusal(StrEnum):
    """Why control refused a command: the tag that begins the refusal's message."""

    NO_POSE = "no_pose"
    """Control has no fresh drone pose (is the simulator running?): try again later."""
    ALREADY_AIRBORNE = "already_airborne"
    """take_off: the drone is not on the ground."""
    NOT_AIRBORNE = "not_airborne"
    """fly: the drone is on the ground or landing; take off first."""
    NOT_FINITE = "not_finite"
    """fly: the target is NaN or infinite."""
    OUTSIDE_ARENA = "outside_arena"
    """fly: the target is beyond the arena's limits."""
    SAME_TARGET = "same_target"
    """fly: the drone is already flying to that target (nothing to do)."""
    ALREADY_LANDING = "already_landing"
    """land: the drone is already coming down."""
    ALREADY_LANDED = "already_landed"
    """land: the drone is on the ground."""


_TAG = re.compile(r"\[([a-z_]+)\] ")


def refusal_message(reason: Refusal, text: str) -> str:
    """A refusal's message: the reason's tag, then ``text`` for people."""
    return f"[{reason.value}] {text}"


def refusal_reason(message: str) -> Refusal | None:
    """The reason tagged at the start of a refusal's message; None when it has no known tag
    (a node that does not tag its refusals, or a reason this version does not know)."""
    match = _TAG.match(message)
    if match is None:
        return None
    try:
        return Refusal(match.group(1))
    except ValueError:
        return None


class FlyCommandRequest(Message):
    """Where to fly: a target in the horizontal plane (metres); NaN and inf are refused."""

    __ros_type__ = "ros_workshop/srv/FlyCommand_Request"

    x: Float32 = 0.0
    y: Float32 = 0.0


class FlyCommandResponse(Message):
    """Whether the command was accepted, and why not (a refusal's message begins with a
    :class:`Refusal` tag)."""

    __ros_type__ = "ros_workshop/srv/FlyCommand_Response"

    success: Bool = False
    message: String = ""


class FlyCommand(ServiceType):
    """Fly to (x, y) at the current altitude."""

    __ros_type__ = "ros_workshop/srv/FlyCommand"
    Request = FlyCommandRequest
    Response = FlyCommandResponse


AiPhase = Annotated[
    Literal["idle", "taking_off", "flying", "landing", "done", "error"], RosPrimitive("string")
]
ControlPhase = Annotated[
    Literal["landed", "taking_off", "flying", "landing"], RosPrimitive("string")
]


class AiStatus(Message):
    """What the AI node is doing: its phase, the boxes visited so far and the planned tour."""

    __ros_type__ = "ros_workshop/msg/AiStatus"
    __ros_comment__ = (
        "# The state of the AI node's box tour.\n"
        "# state: idle, taking_off, flying, landing, done or error\n"
        "# visited: box indices in the order visited; target: the box flown to (-1 when none)\n"
        "# tour: planned order of the box indices still to visit; tour_length: metres of the\n"
        "# planned flight over them, from where the drone was to where it will land"
    )

    header: Header = Field(default_factory=Header)
    state: AiPhase = "idle"
    message: String = ""
    visited: list[Int32] = Field(default_factory=list)
    target: Int32 = -1
    remaining: Int32 = 0
    tour: list[Int32] = Field(default_factory=list)
    tour_length: Float64 = 0.0


class ControlState(Message):
    """The control node's flight phase and the setpoint it is holding."""

    __ros_type__ = "ros_workshop/msg/ControlState"
    __ros_comment__ = (
        "# The control node's flight phase: landed, taking_off, flying or landing\n"
        "# setpoint: the position the drone is being sent to\n"
        "# message: what is wrong (e.g. no drone pose: holding), empty when all is well"
    )

    header: Header = Field(default_factory=Header)
    state: ControlPhase = "landed"
    setpoint: Point = Field(default_factory=Point)
    message: String = ""


class SimWorld(Message):
    """One build of the simulated world; no two builds share an ``id``."""

    __ros_type__ = "ros_workshop/msg/SimWorld"
    __ros_comment__ = (
        "# One build of the simulator's world: at start, at every /simulator/reset, and again\n"
        "# when a restarted simulator builds it. The same seed builds the same boxes, but never\n"
        "# the same id: progress saved for one build is never taken for another.\n"
        "# id: random (64 bits, hex); seed: the simulator's seed; build: 0 for the world it\n"
        "# started with, +1 at every reset; boxes: how many boxes it dropped (the drone world)\n"
        "# or stood in the room (the robot world); world: \"drone\" or \"robot\"; namespaces:\n"
        "# the robot world's robots, where their topics live (\"/\" for one robot, else\n"
        "# \"/robot1\", \"/robot2\", ...)"
    )

    header: Header = Field(default_factory=Header)
    id: String = ""
    seed: UInt32 = 0
    build: UInt32 = 0
    boxes: Int32 = 0
    world: String = "drone"
    namespaces: list[String] = Field(default_factory=list)
