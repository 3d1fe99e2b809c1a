"""std_msgs: Header, ColorRGBA, the primitive wrappers and the multi-arrays."""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from shared_models._message import Bool as _Bool
from shared_models._message import Float32 as _Float32
from shared_models._message import Float64 as _Float64
from shared_models._message import Int8 as _Int8
from shared_models._message import Int16 as _Int16
from shared_models._message import Int32 as _Int32
from shared_models._message import Int64 as _Int64
from shared_models._message import Message, Ros1Only
from shared_models._message import String as _String
from shared_models._message import UInt8 as _UInt8
from shared_models._message import UInt16 as _UInt16
from shared_models._message import UInt32 as _UInt32
from shared_models._message import UInt64 as _UInt64
from shared_models.builtin_interfaces import Time

__all__ = [
    "Bool",
    "ColorRGBA",
    "Empty",
    "Float32",
    "Float32MultiArray",
    "Float64",
    "Float64MultiArray",
    "Header",
    "Int8",
    "Int16",
    "Int32",
    "Int32MultiArray",
    "Int64",
    "MultiArrayDimension",
    "MultiArrayLayout",
    "String",
    "UInt8",
    "UInt16",
    "UInt32",
    "UInt64",
]


class Header(Message):
    """Stamp and frame of a message; ``seq`` (kept from ROS 1) is filled in by the publisher."""

    __ros_type__ = "std_msgs/msg/Header"
    __ros_comment__ = (
        "# Standard metadata for higher-level stamped data types.\n"
        "# seq is kept from ROS 1: the publisher fills it with a consecutive number."
    )

    seq: Annotated[_UInt32, Ros1Only()] = 0
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


class Int8(Message):
    """An 8-bit integer message."""

    __ros_type__ = "std_msgs/msg/Int8"
    data: _Int8 = 0


class Int16(Message):
    """A 16-bit integer message."""

    __ros_type__ = "std_msgs/msg/Int16"
    data: _Int16 = 0


class Int64(Message):
    """A 64-bit integer message."""

    __ros_type__ = "std_msgs/msg/Int64"
    data: _Int64 = 0


class UInt8(Message):
    """An unsigned 8-bit integer message."""

    __ros_type__ = "std_msgs/msg/UInt8"
    data: _UInt8 = 0


class UInt16(Message):
    """An unsigned 16-bit integer message."""

    __ros_type__ = "std_msgs/msg/UInt16"
    data: _UInt16 = 0


class UInt32(Message):
    """An unsigned 32-bit integer message."""

    __ros_type__ = "std_msgs/msg/UInt32"
    data: _UInt32 = 0


class UInt64(Message):
    """An unsigned 64-bit integer message."""

    __ros_type__ = "std_msgs/msg/UInt64"
    data: _UInt64 = 0


class Float32(Message):
    """A 32-bit float message."""

    __ros_type__ = "std_msgs/msg/Float32"
    data: _Float32 = 0.0


class Float64(Message):
    """A 64-bit float message."""

    __ros_type__ = "std_msgs/msg/Float64"
    data: _Float64 = 0.0


class ColorRGBA(Message):
    """A colour: red, green, blue and alpha, each 0 to 1 (all zero, transparent, by default)."""

    __ros_type__ = "std_msgs/msg/ColorRGBA"

    r: _Float32 = 0.0
    g: _Float32 = 0.0
    b: _Float32 = 0.0
    a: _Float32 = 0.0


class MultiArrayDimension(Message):
    """One dimension of a multi-array: its label, size and stride."""

    __ros_type__ = "std_msgs/msg/MultiArrayDimension"

    label: _String = ""  # label of given dimension
    size: _UInt32 = 0  # size of given dimension (in type units)
    stride: _UInt32 = 0  # stride of given dimension


class MultiArrayLayout(Message):
    """How a multi-array's flat ``data`` is laid out in dimensions."""

    __ros_type__ = "std_msgs/msg/MultiArrayLayout"
    __ros_comment__ = (
        "# The multiarray declares a generic multi-dimensional array of a\n"
        "# particular data type.  Dimensions are ordered from outer most\n"
        "# to inner most.\n"
        "# data_offset: padding elements at front of data"
    )

    dim: list[MultiArrayDimension] = Field(default_factory=list)
    data_offset: _UInt32 = 0


class Float32MultiArray(Message):
    """A multi-dimensional array of 32-bit floats."""

    __ros_type__ = "std_msgs/msg/Float32MultiArray"
    __ros_comment__ = "# This was originally provided as an example message."

    layout: MultiArrayLayout = Field(default_factory=MultiArrayLayout)
    data: list[_Float32] = Field(default_factory=list)


class Float64MultiArray(Message):
    """A multi-dimensional array of 64-bit floats."""

    __ros_type__ = "std_msgs/msg/Float64MultiArray"
    __ros_comment__ = "# This was originally provided as an example message."

    layout: MultiArrayLayout = Field(default_factory=MultiArrayLayout)
    data: list[_Float64] = Field(default_factory=list)


class Int32MultiArray(Message):
    """A multi-dimensional array of 32-bit integers."""

    __ros_type__ = "std_msgs/msg/Int32MultiArray"
    __ros_comment__ = "# This was originally provided as an example message."

    layout: MultiArrayLayout = Field(default_factory=MultiArrayLayout)
    data: list[_Int32] = Field(default_factory=list)


class Empty(Message):
    """A message with no fields."""

    __ros_type__ = "std_msgs/msg/Empty"
