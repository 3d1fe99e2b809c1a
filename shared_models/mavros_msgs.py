"""mavros_msgs: the autopilot's State and the PositionTarget setpoint."""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field

from shared_models._message import Bool, Float32, Message, String, UInt8, UInt16
from shared_models.geometry_msgs import Point, Vector3
from shared_models.std_msgs import Header

__all__ = ["PositionTarget", "State"]


class State(Message):
    """The autopilot's state: link, arming, mode and MAV_STATE system status."""

    __ros_type__ = "mavros_msgs/msg/State"
    __ros_comment__ = (
        "# Current autopilot state\n"
        "#\n"
        "# Known modes listed here:\n"
        "# http://wiki.ros.org/mavros/CustomModes\n"
        "#\n"
        "# For system_status values\n"
        "# see https://mavlink.io/en/messages/common.html#MAV_STATE"
    )

    header: Header = Field(default_factory=Header)
    connected: Bool = False
    armed: Bool = False
    guided: Bool = False
    manual_input: Bool = False
    mode: String = ""
    system_status: UInt8 = 0


class PositionTarget(Message):
    """A local setpoint (SET_POSITION_TARGET_LOCAL_NED); ``type_mask`` says which parts to ignore.

    Example::

        PositionTarget(
            coordinate_frame=PositionTarget.FRAME_LOCAL_NED,
            type_mask=PositionTarget.IGNORE_VX | PositionTarget.IGNORE_VY | PositionTarget.IGNORE_VZ,
            position=Point(x=1.0, y=2.0, z=3.0),
        )
    """

    __ros_type__ = "mavros_msgs/msg/PositionTarget"
    __ros_comment__ = (
        "# Message for SET_POSITION_TARGET_LOCAL_NED\n"
        "#\n"
        "# Some complex system requires all feautures that mavlink\n"
        "# message provide. See issue #402."
    )
    __ros_constants__ = (
        "FRAME_LOCAL_NED",
        "FRAME_LOCAL_OFFSET_NED",
        "FRAME_BODY_NED",
        "FRAME_BODY_OFFSET_NED",
        "IGNORE_PX",
        "IGNORE_PY",
        "IGNORE_PZ",
        "IGNORE_VX",
        "IGNORE_VY",
        "IGNORE_VZ",
        "IGNORE_AFX",
        "IGNORE_AFY",
        "IGNORE_AFZ",
        "FORCE",
        "IGNORE_YAW",
        "IGNORE_YAW_RATE",
    )

    FRAME_LOCAL_NED: ClassVar[UInt8] = 1
    FRAME_LOCAL_OFFSET_NED: ClassVar[UInt8] = 7
    FRAME_BODY_NED: ClassVar[UInt8] = 8
    FRAME_BODY_OFFSET_NED: ClassVar[UInt8] = 9

    IGNORE_PX: ClassVar[UInt16] = 1  # position ignore flags
    IGNORE_PY: ClassVar[UInt16] = 2
    IGNORE_PZ: ClassVar[UInt16] = 4
    IGNORE_VX: ClassVar[UInt16] = 8  # velocity vector ignore flags
    IGNORE_VY: ClassVar[UInt16] = 16
    IGNORE_VZ: ClassVar[UInt16] = 32
    IGNORE_AFX: ClassVar[UInt16] = 64  # acceleration/force vector ignore flags
    IGNORE_AFY: ClassVar[UInt16] = 128
    IGNORE_AFZ: ClassVar[UInt16] = 256
    FORCE: ClassVar[UInt16] = 512  # force in af vector flag
    IGNORE_YAW: ClassVar[UInt16] = 1024
    IGNORE_YAW_RATE: ClassVar[UInt16] = 2048

    header: Header = Field(default_factory=Header)
    coordinate_frame: UInt8 = 0
    type_mask: UInt16 = 0
    position: Point = Field(default_factory=Point)
    velocity: Vector3 = Field(default_factory=Vector3)
    acceleration_or_force: Vector3 = Field(default_factory=Vector3)
    yaw: Float32 = 0.0
    yaw_rate: Float32 = 0.0
