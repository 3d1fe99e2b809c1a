"""``rospy.Publisher`` and ``rospy.Subscriber``.

    publisher = rospy.Publisher("perception/boxes", Polygon, queue_size=1)
    publisher.publish(polygon)                  # or publish(points=[...]), publish(Point(1, 2, 3)...)
    rospy.Subscriber("/simulator/boxes", PoseArray, callback)

Threads as in rospy: each Subscriber calls its callback on a thread of its own (never the main
thread, never the bridge's loop), one message at a time and in order, so the program's main
loop and blocking service calls inside callbacks all work. Messages wait in the subscriber's
queue (``queue_size``: the newest are kept; None keeps all) while its callback runs. Publishing
is safe from any thread (the rclpy façade's publisher does the hand-over to the loop).
"""

from __future__ import annotations

import collections
import threading
from collections.abc import Callable
from typing import Any

from services.ros.bridge import bridge
from services.ros.rclpy.publisher import Publisher as LoopPublisher
from services.ros.rospy.core import process, report
from services.ros.rospy.graph import graph_topic
from services.ros.rospy.log import logwarn_once
from services.runtime.lockstep.activity import ACTIVITY
from shared_models import Message

__all__ = ["Publisher", "Subscriber", "check_message_class"]

_LINK_DEPTH = 100  # what the SDK keeps per link; the subscriber's own queue_size is applied here


def check_message_class(data_class: Any, what: str) -> None:
    """A message class (``geometry_msgs.msg.PoseArray``), or TypeError naming ``what`` needed one."""
    if not (isinstance(data_class, type) and issubclass(data_class, Message) and data_class.__ros_type__):
        raise TypeError(f"{what} needs a message class such as geometry_msgs.msg.PoseArray, got {data_class!r}")


def _ros1_type(data_class: type[Message]) -> str:
    return data_class.__ros_type__.replace("/msg/", "/")


class Publisher:
    """Publishes ``data_class`` messages on ``name``; ``latch=True`` sends the last one to every
    subscriber that connects later."""

    def __init__(
        self, name: str, data_class: type[Message], subscriber_listener: Any = None, tcp_nodelay: bool = False,
        latch: bool = False, headers: Any = None, queue_size: int | None = None,
    ) -> None:  # fmt: skip
        node = process.require_node("rospy.Publisher")
        check_message_class(data_class, "rospy.Publisher")
        if queue_size is None:
            logwarn_once(
                "Publisher of %s created without queue_size: give it one (rospy.Publisher(..., queue_size=1))", name
            )
        depth = queue_size if isinstance(queue_size, int) and queue_size > 0 else _LINK_DEPTH
        runtime = bridge.call(lambda: node.create_publisher(data_class, name, depth, latched=latch))
        self._loop_publisher = LoopPublisher(runtime, None, None)
        self.name = self.resolved_name = runtime.topic_name
        self.data_class = data_class
        self.type = _ros1_type(data_class)

    def publish(self, *args: Any, **kwds: Any) -> None:
        """Publish a message, or build one from the arguments as rospy does:
        ``publish(msg)``, ``publish(x, y, z)`` (fields in order), ``publish(x=1.0)``."""
        if len(args) == 1 and not kwds and isinstance(args[0], Message):
            msg = args[0]
        else:
            msg = self.data_class(*args, **kwds)
        self._loop_publisher.publish(msg)

    def get_num_connections(self) -> int:
        """How many subscribers this publisher sends to now."""
        return self._loop_publisher.get_subscription_count()

    def unregister(self) -> None:
        """Stop publishing (later publishes do nothing)."""
        self._loop_publisher.destroy()


class Subscriber:
    """Calls ``callback(msg)`` (or ``callback(msg, callback_args)``) for each message on ``name``,
    on the subscriber's own thread."""

    def __init__(
        self, name: str, data_class: type[Message], callback: Callable[..., Any] | None = None,
        callback_args: Any = None, queue_size: int | None = None, buff_size: int = 65536, tcp_nodelay: bool = False,
    ) -> None:  # fmt: skip
        node = process.require_node("rospy.Subscriber")
        check_message_class(data_class, "rospy.Subscriber")
        if callback is not None and not callable(callback):
            raise TypeError(f"rospy.Subscriber's callback must be a function, got {callback!r}")
        self.data_class = data_class
        self.type = _ros1_type(data_class)
        self.callback = callback
        self.callback_args = callback_args
        self.name = self.resolved_name = node.resolve_topic_name(name)
        self._what = f"the subscriber callback of {self.name}"
        self._messages: collections.deque[Message] = collections.deque(maxlen=queue_size or None)
        self._arrival = threading.Condition()
        self._unregistered = False
        self._delivering = False
        ACTIVITY.watch(self, self._has_work)  # a lockstep run waits for its callbacks
        self._thread = threading.Thread(target=self._deliver, name=f"rospy subscriber {self.name}", daemon=True)
        self._thread.start()
        bridge.call(lambda: node.create_subscription(data_class, name, self._arrived, _LINK_DEPTH))

    def _arrived(self, msg: Message) -> None:
        """A message from the SDK (on the bridge's loop): queue it for the thread."""
        with self._arrival:
            if self._unregistered:
                return
            self._messages.append(msg)
            self._arrival.notify()

    def _has_work(self) -> bool:
        return bool(self._messages) or self._delivering

    def _deliver(self) -> None:
        while True:
            with self._arrival:
                self._delivering = False
                while not self._messages and not self._unregistered:
                    self._arrival.wait()
                if self._unregistered:
                    return
                msg = self._messages.popleft()
                self._delivering = True
            callback = self.callback
            if callback is None or process.is_shutdown():
                continue
            try:
                callback(msg) if self.callback_args is None else callback(msg, self.callback_args)
            except Exception as error:
                report(error, self._what)

    def get_num_connections(self) -> int:
        """How many publishers of the topic there are in the graph."""
        return len(graph_topic(self.name).get("publishers", []))

    def unregister(self) -> None:
        """Stop calling the callback (the node stays subscribed in the graph until it stops)."""
        with self._arrival:
            self._unregistered = True
            self._messages.clear()
            self._arrival.notify_all()
