"""ROS 1's ``tf`` package, as Noetic has it (on tf2): a listener that answers in tuples, a
broadcaster that takes them, ``tf.transformations``, and tf2's exceptions under tf's names.

    listener = tf.TransformListener()
    listener.waitForTransform('/odom', '/base_link', rospy.Time(0), rospy.Duration(4.0))
    (trans, rot) = listener.lookupTransform('/odom', '/base_link', rospy.Time(0))
    roll, pitch, yaw = tf.transformations.euler_from_quaternion(rot)

Frame names may start with '/', as tf allowed (it is dropped).
"""

from __future__ import annotations

from services.ros.tf import transformations
from services.ros.tf.broadcaster import TransformBroadcaster
from services.ros.tf.listener import Transformer, TransformerROS, TransformListener
from services.ros.tf2_ros.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    LookupException,
)
from services.ros.tf2_ros.exceptions import TransformException as Exception  # noqa: A004 (tf's name)

__all__ = [
    "ConnectivityException",
    "Exception",
    "ExtrapolationException",
    "LookupException",
    "TransformBroadcaster",
    "TransformListener",
    "Transformer",
    "TransformerROS",
    "transformations",
]
