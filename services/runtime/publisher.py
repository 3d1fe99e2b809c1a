"""Publishers: ``node.create_publisher(PointStamped, "/my_point", 10)``."""

from __future__ import annotations

from collections.abc import Callable
from typing import Generic, TypeVar

from services.runtime.endpoint import TopicEndpoint
from shared_models import Message

__all__ = ["Publisher"]

M = TypeVar("M", bound=Message)


class Publisher(Generic[M]):
    """Publishes messages of one type on one topic; made by :meth:`Node.create_publisher`."""

    def __init__(self, endpoint: TopicEndpoint, msg_type: type[M], queue_size: int) -> None:
        self._endpoint = endpoint
        self.msg_type = msg_type
        self.topic_name = endpoint.name
        self.queue_size = queue_size
        self._has_header = "header" in msg_type.model_fields
        self._seq = 0

    def publish(self, msg: M | str) -> None:
        """Publish ``msg`` to every subscriber; fills ``header.seq`` when the type has a header.

        A ``str`` is a message already serialised (its JSON frame, as rclpy's ``publish`` takes
        a serialised message): sent as it is, unvalidated, its ``seq`` untouched (``bag play``).
        Never blocks: slow readers lose their oldest messages instead of slowing this call.
        """
        if isinstance(msg, str):
            self._endpoint.dispatch_frame(msg)
            return
        if type(msg) is not self.msg_type:
            raise TypeError(
                f"publisher of {self.topic_name} takes {self.msg_type.__ros_type__} "
                f"({self.msg_type.__name__}), not {type(msg).__name__}"
            )
        if self._has_header:
            _number(msg, self._next_seq())
        self._endpoint.dispatch(msg)  # serialised once per encoding that a reader wants

    def publish_built(self, build: Callable[[], M]) -> None:
        """Publish the message ``build()`` makes, made only if someone reads the topic now (or
        later asks for the latest with ``GET /TOPIC``): for a hot loop, such as the simulator's
        at ``--speed max``, whose many topics are often unread. ``header.seq`` counts it either way.
        """
        if not self._has_header:
            self._endpoint.dispatch_deferred(build)
            return
        seq = self._next_seq()
        self._endpoint.dispatch_deferred(lambda: _number(build(), seq))

    def _next_seq(self) -> int:
        self._seq = (self._seq + 1) & 0xFFFFFFFF
        return self._seq

    def get_subscription_count(self) -> int:
        """How many remote readers and local subscriptions receive this topic now."""
        return len(self._endpoint.outboxes) + len(self._endpoint.subscriptions)


def _number(msg: M, seq: int) -> M:
    """``msg`` with ``header.seq`` set, straight into the field: messages check assigned values,
    but this is an int we made, and the check would cost a fifth of a publish."""
    msg.header.__dict__["seq"] = seq  # type: ignore[attr-defined]
    return msg
