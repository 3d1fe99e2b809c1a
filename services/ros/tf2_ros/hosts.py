"""Which node tf2's listeners and broadcasters live on: the rclpy node a ROS 2 program hands
them, or the process's rospy node (``rospy.init_node``) for a ROS 1 program, which hands none.

Subscriptions are made on the SDK node underneath (their callbacks run on Skydeck's event loop,
filling the buffer there); publishers are the client library's own, safe from any thread.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

from services.ros.bridge import bridge
from services.ros.rclpy.node import Node as RclpyNode
from services.ros.rospy.core import process
from services.ros.rospy.exceptions import ROSInitException
from shared_models.tf2_msgs import TFMessage

__all__ = ["Host", "TFPublisher", "host_for"]


class TFPublisher(Protocol):
    def publish(self, msg: Any) -> None: ...


class Host:
    """A node to subscribe and publish TF on."""

    def __init__(self, runtime_node: Any, rclpy_node: RclpyNode | None) -> None:
        self._runtime = runtime_node
        self.rclpy_node = rclpy_node

    def subscribe(self, topic: str, callback: Callable[[TFMessage], None], depth: int) -> None:
        """``callback(msg)`` for each TFMessage on ``topic``, on the event loop."""
        runtime = self._runtime
        bridge.call(lambda: runtime.create_subscription(TFMessage, topic, callback, depth))

    def publisher(self, topic: str, depth: int, *, latched: bool, qos: Any = None) -> TFPublisher:
        """A TFMessage publisher on ``topic`` (``latched``: later subscribers get the last one)."""
        if self.rclpy_node is not None:
            from services.ros.rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile

            if qos is None:
                durability = DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE
                qos = QoSProfile(depth=depth, durability=durability, history=HistoryPolicy.KEEP_LAST)
            return self.rclpy_node.create_publisher(TFMessage, topic, qos)
        from services.ros.rospy.topics import Publisher

        return Publisher(topic, TFMessage, queue_size=depth, latch=latched)


def host_for(node: Any, what: str, *, own_node_name: str | None = None) -> Host:
    """The host for ``node`` as given to ``what`` (see the module docstring); ``own_node_name``:
    with ``node=None`` under rclpy, a node of this name is made (as tf2_ros's listener does)."""
    if isinstance(node, RclpyNode):
        return Host(node._rclpy_node, node)
    if node is not None and not isinstance(node, int):
        raise TypeError(f"{what} takes an rclpy Node (ROS 2), or nothing after rospy.init_node (ROS 1); got {node!r}")
    if process.node is not None:
        return Host(process.node, None)
    if own_node_name is not None:
        from services.ros.rclpy.context import default_context

        if default_context.ok():
            own = RclpyNode(own_node_name, enable_rosout=False, start_parameter_services=False)
            return Host(own._rclpy_node, own)
    raise ROSInitException(
        f"{what} needs a node: in ROS 2 pass yours ({what}(..., node)); in ROS 1 call rospy.init_node('name') first"
    )
