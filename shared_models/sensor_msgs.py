"""sensor_msgs: CompressedImage."""

from __future__ import annotations

from pydantic import ConfigDict, Field

from shared_models._message import Message, String, UInt8Array
from shared_models.std_msgs import Header

__all__ = ["CompressedImage"]


class CompressedImage(Message):
    """A compressed image (JPEG or PNG bytes); ``data`` travels in JSON as base64.

    Example::

        CompressedImage(header=Header(frame_id="camera"), format="jpeg", data=jpeg_bytes)
    """

    # Base64 in JSON, as rosbridge does: a JSON array of ints would be 3-4x bigger. UInt8Array
    # writes the standard alphabet and also accepts a list of ints or, from Python, base64 text.
    model_config = ConfigDict(ser_json_bytes="base64", val_json_bytes="base64")

    __ros_type__ = "sensor_msgs/msg/CompressedImage"
    __ros_comment__ = (
        "# This message contains a compressed image.\n"
        "# format: the image format, e.g. jpeg or png.\n"
        "# data: the compressed image buffer (base64 in JSON)."
    )

    header: Header = Field(default_factory=Header)
    format: String = ""
    data: UInt8Array = b""
