"""``tf2_ros``: coordinate frames over time, as ROS 1's and ROS 2's tf2_ros have them, over
Skydeck's topics.

    from tf2_ros import Buffer, TransformListener, TransformException
    from rclpy.time import Time

    self.tf_buffer = Buffer()
    self.tf_listener = TransformListener(self.tf_buffer, self)
    try:
        t = self.tf_buffer.lookup_transform('odom', 'base_link', Time())
    except TransformException as ex:
        self.get_logger().info(f'Could not transform base_link to odom: {ex}')

- :mod:`.buffer`: ``Buffer`` (tf2's BufferCore, :mod:`.buffer_core`, and waits on it);
- :mod:`.transform_listener`, :mod:`.transform_broadcaster`, :mod:`.static_transform_broadcaster`:
  ``/tf`` and ``/tf_static`` on the program's node (rclpy's, or rospy's);
- :mod:`.exceptions`: tf2's exceptions, with tf2's messages.

A ROS 2 program hands its node to the listener and broadcasters; a ROS 1 program hands none
and they use its rospy node. What differs from ROS is in docs/ros.md ("tf2").
"""

from __future__ import annotations

from services.ros.errors import not_provided_attributes
from services.ros.tf2_ros.buffer import Buffer
from services.ros.tf2_ros.buffer_core import BufferCore
from services.ros.tf2_ros.buffer_interface import TransformRegistration, TypeException
from services.ros.tf2_ros.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from services.ros.tf2_ros.static_transform_broadcaster import StaticTransformBroadcaster
from services.ros.tf2_ros.transform_broadcaster import TransformBroadcaster
from services.ros.tf2_ros.transform_listener import TransformListener

__all__ = [
    "Buffer",
    "BufferCore",
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "StaticTransformBroadcaster",
    "TimeoutException",
    "TransformBroadcaster",
    "TransformException",
    "TransformListener",
    "TransformRegistration",
    "TypeException",
]

_NOT_PROVIDED = frozenset({"BufferClient", "MessageFilter", "StaticTransformListener", "MultipleStaticTransformBroadcaster"})


__getattr__ = not_provided_attributes("tf2_ros", _NOT_PROVIDED)
