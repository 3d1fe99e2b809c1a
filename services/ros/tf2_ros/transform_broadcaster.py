"""``tf2_ros.TransformBroadcaster``: publishes transforms on ``/tf``.

    self.tf_broadcaster = TransformBroadcaster(self)       # ROS 2: the node
    broadcaster = tf2_ros.TransformBroadcaster()           # ROS 1: after rospy.init_node
    broadcaster.sendTransform(t)                           # a TransformStamped, or a list of them
"""

from __future__ import annotations

from typing import Any

from services.ros.tf2_ros.hosts import host_for
from shared_models.geometry_msgs import TransformStamped
from shared_models.tf2_msgs import TFMessage

__all__ = ["TransformBroadcaster", "transforms_of"]

_DEPTH = 100


def transforms_of(transform: Any, what: str) -> list[TransformStamped]:
    """``sendTransform``'s argument as a list, each item checked."""
    transforms = list(transform) if isinstance(transform, list | tuple) else [transform]
    for item in transforms:
        if not isinstance(item, TransformStamped):
            raise TypeError(f"{what} takes a geometry_msgs TransformStamped or a list of them, got {type(item).__name__}")
    return transforms


class TransformBroadcaster:
    """Sends transforms on ``/tf`` (dynamic: each one a sample of its link's history)."""

    def __init__(self, node: Any = None, qos: Any = None, queue_size: int = _DEPTH) -> None:
        if isinstance(node, int) and not isinstance(node, bool):  # ROS 1's TransformBroadcaster(queue_size)
            node, queue_size = None, node
        self.pub_tf = host_for(node, "TransformBroadcaster").publisher("/tf", queue_size, latched=False, qos=qos)

    def sendTransform(self, transform: TransformStamped | list[TransformStamped]) -> None:
        """Publish one transform or a list of them in one message."""
        self.pub_tf.publish(TFMessage(transforms=transforms_of(transform, "sendTransform")))
