"""``rclpy.publisher.Publisher``: ``self.create_publisher(Twist, 'cmd_vel', 10).publish(msg)``.

Safe from any thread. The message is checked in the caller's thread (a wrong type raises there,
on the user's line); from a thread other than the bridge's loop, a copy is handed to the loop,
so the program may change and publish the same message object again at once, as with rclpy
(which serialises inside ``publish``).
"""

from __future__ import annotations

from typing import Any

from services.ros.bridge import bridge
from services.runtime.publisher import Publisher as RuntimePublisher

__all__ = ["Publisher"]


class Publisher:
    """Publishes one message type on one topic (made by ``Node.create_publisher``)."""

    def __init__(self, publisher: RuntimePublisher[Any], qos_profile: Any, node: Any) -> None:
        self._publisher = publisher
        self.msg_type = publisher.msg_type
        self.qos_profile = qos_profile
        self._node = node
        self._destroyed = False

    @property
    def topic_name(self) -> str:
        return self._publisher.topic_name

    @property
    def topic(self) -> str:
        return self._publisher.topic_name

    def publish(self, msg: Any) -> None:
        """Send ``msg`` to every subscriber (never blocks)."""
        if type(msg) is not self.msg_type:
            raise TypeError(
                f"Expected {self.msg_type.__ros_type__} ({self.msg_type.__name__}) on {self.topic_name}, "
                f"got {type(msg).__name__}"
            )
        if self._destroyed:
            return
        if bridge.in_loop_thread():
            self._publisher.publish(msg)
        else:
            bridge.call_soon(self._publisher.publish, msg.model_copy(deep=True))

    def get_subscription_count(self) -> int:
        """How many subscribers receive this topic from this publisher now."""
        return bridge.call(self._publisher.get_subscription_count)

    def wait_for_all_acked(self, timeout: Any = None) -> bool:
        return True  # links are TCP: what was sent is delivered or the link is gone

    def assert_liveliness(self) -> None:
        pass

    def destroy(self) -> None:
        """Stop publishing (later calls to publish do nothing)."""
        self._destroyed = True
