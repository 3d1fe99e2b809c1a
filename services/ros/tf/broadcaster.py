"""ROS 1's ``tf.TransformBroadcaster``: transforms given as tuples, on ``/tf``.

    br = tf.TransformBroadcaster()
    br.sendTransform((x, y, 0), tf.transformations.quaternion_from_euler(0, 0, theta),
                     rospy.Time.now(), 'turtle1', 'world')            # child, then parent
"""

from __future__ import annotations

from typing import Any

from services.ros.tf2_ros.transform_broadcaster import TransformBroadcaster as Tf2Broadcaster
from shared_models.geometry_msgs import Quaternion, Transform, TransformStamped, Vector3
from shared_models.std_msgs import Header

__all__ = ["TransformBroadcaster"]


class TransformBroadcaster:
    """Publishes on ``/tf`` from the process's rospy node."""

    def __init__(self, queue_size: int = 100) -> None:
        self._broadcaster = Tf2Broadcaster(None, queue_size=queue_size)

    def sendTransform(self, translation: Any, rotation: Any, time: Any, child: str, parent: str) -> None:
        """The transform of ``child`` in ``parent`` at ``time``: ``translation`` (x, y, z) and
        ``rotation`` (x, y, z, w)."""
        x, y, z = (float(v) for v in translation)
        qx, qy, qz, qw = (float(v) for v in rotation)
        self.sendTransformMessage(
            TransformStamped(
                header=Header(stamp=time, frame_id=parent),
                child_frame_id=child,
                transform=Transform(translation=Vector3(x=x, y=y, z=z), rotation=Quaternion(x=qx, y=qy, z=qz, w=qw)),
            )
        )

    def sendTransformMessage(self, transform: TransformStamped) -> None:
        """Publish a TransformStamped (or a list of them)."""
        self._broadcaster.sendTransform(transform)
