"""``tf.msg`` (ROS 1): ``tfMessage``, tf's old name for ``tf2_msgs/TFMessage`` (the same type)."""

from __future__ import annotations

from shared_models.tf2_msgs import TFMessage

__all__ = ["tfMessage"]

tfMessage = TFMessage  # noqa: N816 (tf's name)
