"""ros_workshop: the workshop's own types (the fly command, the AI's and the controller's state)."""

from __future__ import annotations

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
)
from shared_models.geometry_msgs import Point
from shared_models.std_msgs import Header

__all__ = [
    "AiStatus",
    "ControlState",
    "FlyCommand",
    "FlyCommandRequest",
    "FlyCommandResponse",
]


class FlyCommandRequest(Message):
    """Where to fly: a target in the horizontal plane (metres); NaN and inf are refused."""

    __ros_type__ = "ros_workshop/srv/FlyCommand_Request"

    x: Float32 = 0.0
    y: Float32 = 0.0


class FlyCommandResponse(Message):
    """Whether the command was accepted, and why not."""

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
        "# tour: planned order of the box indices still to visit; tour_length in metres"
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
