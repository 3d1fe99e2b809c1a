"""tf2_msgs: TFMessage, the message of ``/tf`` and ``/tf_static``."""

from __future__ import annotations

from pydantic import Field

from shared_models._message import Message
from shared_models.geometry_msgs import TransformStamped

__all__ = ["TFMessage"]


class TFMessage(Message):
    """A batch of transforms, each an edge of the TF tree (parent ``header.frame_id`` to
    ``child_frame_id``)."""

    __ros_type__ = "tf2_msgs/msg/TFMessage"

    transforms: list[TransformStamped] = Field(default_factory=list)
