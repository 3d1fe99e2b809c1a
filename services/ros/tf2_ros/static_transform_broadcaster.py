"""``tf2_ros.StaticTransformBroadcaster``: publishes links that never move on ``/tf_static``.

    broadcaster = StaticTransformBroadcaster(self)         # ROS 2: the node; ROS 1: no argument
    broadcaster.sendTransform([t1, t2])

Latched, as ROS's: a listener that starts later still gets them. Transforms accumulate, as
tf2_ros's do: each send republishes every link this broadcaster has sent (a later one for the
same child frame replaces the earlier), so two calls to ``sendTransform`` keep both links.
"""

from __future__ import annotations

from typing import Any

from services.ros.tf2_ros.hosts import host_for
from services.ros.tf2_ros.transform_broadcaster import transforms_of
from shared_models.geometry_msgs import TransformStamped
from shared_models.tf2_msgs import TFMessage

__all__ = ["StaticTransformBroadcaster"]


class StaticTransformBroadcaster:
    """Sends static transforms on ``/tf_static`` (see the module docstring)."""

    def __init__(self, node: Any = None, qos: Any = None, queue_size: int = 1) -> None:
        if isinstance(node, int) and not isinstance(node, bool):  # ROS 1's StaticTransformBroadcaster(queue_size)
            node, queue_size = None, node
        self.pub_tf = host_for(node, "StaticTransformBroadcaster").publisher(
            "/tf_static", queue_size, latched=True, qos=qos
        )
        self._links: dict[str, TransformStamped] = {}

    def sendTransform(self, transform: TransformStamped | list[TransformStamped]) -> None:
        """Add (or replace, by child frame) these links and publish them all."""
        for item in transforms_of(transform, "sendTransform"):
            self._links[item.child_frame_id] = item.model_copy(deep=True)
        self.pub_tf.publish(TFMessage(transforms=list(self._links.values())))
