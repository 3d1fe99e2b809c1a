"""``rclpy.subscription.Subscription``: messages queue here (keep-last: the QoS depth, the
oldest dropped) until the executor that spins the node runs the callback with each."""

from __future__ import annotations

import collections
import threading
from collections.abc import Callable
from typing import Any

from services.ros.rclpy.callback_groups import CallbackGroup
from services.ros.rclpy.waitable import Job, Owner, Waitable, run_callback

__all__ = ["Subscription"]


class Subscription(Waitable):
    """Calls ``callback(msg)`` for each message of a topic (made by ``Node.create_subscription``)."""

    def __init__(
        self,
        node: Owner,
        msg_type: type[Any],
        topic: str,
        callback: Callable[[Any], Any],
        qos_profile: Any,
        callback_group: CallbackGroup | None,
    ) -> None:
        super().__init__(node, callback_group)
        self.msg_type = msg_type
        self.topic_name = topic
        self.callback = callback
        self.qos_profile = qos_profile
        self.what = f"the subscription callback of {topic}"
        self._messages: collections.deque[Any] = collections.deque(maxlen=qos_profile.queue_depth)
        self._lock = threading.Lock()
        self._destroyed = False

    @property
    def topic(self) -> str:
        return self.topic_name

    def _arrived(self, msg: Any) -> None:
        """A message from the SDK (on the bridge's loop)."""
        if self._destroyed:
            return
        with self._lock:
            self._messages.append(msg)
        self._notify()

    def _has_work(self) -> bool:
        return bool(self._messages)

    def _take(self) -> Job | None:
        with self._lock:
            if not self._messages or self._destroyed:
                return None
            msg = self._messages.popleft()
        return lambda: run_callback(self.callback, msg)

    def destroy(self) -> None:
        """Stop delivering messages (the node leaves the topic when it stops)."""
        self._destroyed = True
        with self._lock:
            self._messages.clear()
