"""std_msgs: Header and the primitive wrappers."""

from __future__ import annotations

from pydantic import Field

from shared_models._message import Bool as _Bool
from shared_models._message import Float64 as _Float64
from shared_models._message import Int32 as _Int32
from shared_models._message import Message, UInt32
from shared_models._message import String as _String
from shared_models.builtin_interfaces import Time

__all__ = ["Bool", "Empty", "Float64", "Header", "Int32", "String"]


class Header(Message):
    """Stamp and frame of a message; ``seq`` (kept from ROS 1) is filled in by the publisher."""

    __ros_type__ = "std_msgs/msg/Header"
    __ros_comment__ = (
        "# Standard metadata for higher-level stamped data types.\n"
        "# seq is kept from ROS 1: the publisher fills it with a consecutive number."
    )

    seq: UInt32 = 0
    stamp: Time = Field(default_factory=Time)
    frame_id: _String = ""


# The primitive wrappers keep ROS's field name `data`. Their class names shadow the field aliases
# of shared_models._message on purpose: `from shared_models.std_msgs import String` is the message.
class String(Message):
    """A string message."""

    __ros_type__ = "std_msgs/msg/String"
    data: _String = ""


class Bool(Message):
    """A boolean message."""

    __ros_type__ = "std_msgs/msg/Bool"
    data: _Bool = False


class Int32(Message):
    """A 32-bit integer message."""

    __ros_type__ = "std_msgs/msg/Int32"
    data: _Int32 = 0


class Float64(Message):
    """A 64-bit float message."""

    __ros_type__ = "std_msgs/msg/Float64"
    data: _Float64 = 0.0


class Empty(Message):
    """A message with no fields."""

    __ros_type__ = "std_msgs/msg/Empty"
