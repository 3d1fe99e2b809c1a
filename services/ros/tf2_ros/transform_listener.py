"""``tf2_ros.TransformListener``: fills a Buffer from ``/tf`` and ``/tf_static``.

    self.tf_buffer = Buffer()
    self.tf_listener = TransformListener(self.tf_buffer, self)     # ROS 2: the node
    listener = tf2_ros.TransformListener(buffer)                   # ROS 1: after rospy.init_node

``/tf`` samples join each link's history (``cache_time`` of it); ``/tf_static`` links are
latched by their broadcasters, so a listener started late still hears them. The subscriptions
are the node's (they show in the graph), and fill the buffer on Skydeck's event loop as messages
arrive, whether or not the program spins: as tf2_ros's ``spin_thread=True``, always.
"""

from __future__ import annotations

from typing import Any

from services.ros.rclpy.qos import qos_profile
from services.ros.tf2_ros.buffer_core import BufferCore
from services.ros.tf2_ros.hosts import host_for
from shared_models.tf2_msgs import TFMessage

__all__ = ["DEFAULT_STATIC_TF_TOPIC", "DEFAULT_TF_TOPIC", "TransformListener"]

DEFAULT_TF_TOPIC = "/tf"
DEFAULT_STATIC_TF_TOPIC = "/tf_static"
_DEPTH = 100  # tf2_ros's history depth for both topics
_AUTHORITY = "default_authority"


class TransformListener:
    """Subscribes ``buffer`` to the TF topics (see the module docstring)."""

    def __init__(
        self, buffer: BufferCore, node: Any = None, *args: Any, spin_thread: bool = False, qos: Any = None,
        static_qos: Any = None, tf_topic: str = DEFAULT_TF_TOPIC, tf_static_topic: str = DEFAULT_STATIC_TF_TOPIC,
        static_only: bool = False, **ros1_options: Any,
    ) -> None:  # fmt: skip
        if not isinstance(buffer, BufferCore):
            raise TypeError(f"TransformListener takes a tf2_ros.Buffer first, got {type(buffer).__name__}")
        # ROS 1's TransformListener(buffer, queue_size=None, buff_size=65536, tcp_nodelay=False):
        # the node comes from rospy; the rest are transport settings Skydeck has no use for.
        self.buffer = buffer
        self._host = host_for(node, "TransformListener", own_node_name=f"transform_listener_impl_{id(self):010x}")
        self.node = self._host.rclpy_node
        self._listening = True
        if not static_only:
            self._host.subscribe(tf_topic, self.callback, _depth(qos))
        self._host.subscribe(tf_static_topic, self.static_callback, _depth(static_qos))

    def callback(self, data: TFMessage) -> None:
        """A ``/tf`` message: each transform joins its link's history."""
        if self._listening:
            for transform in data.transforms:
                self.buffer.set_transform(transform, _AUTHORITY)

    def static_callback(self, data: TFMessage) -> None:
        """A ``/tf_static`` message: each transform sets its static link."""
        if self._listening:
            for transform in data.transforms:
                self.buffer.set_transform_static(transform, _AUTHORITY)

    def unregister(self) -> None:
        """Stop filling the buffer (the node stays subscribed in the graph until it stops)."""
        self._listening = False


def _depth(qos: Any) -> int:
    return _DEPTH if qos is None else qos_profile(qos).queue_depth
