"""Subscriptions: ``node.create_subscription(PointStamped, "/my_point", callback, 10)``."""

from __future__ import annotations

import asyncio
import logging
from collections import deque
from collections.abc import Callable
from typing import Any

from services.runtime.callbacks import call_user
from shared_models import Message

__all__ = ["Subscription"]


class Subscription:
    """Calls ``callback(msg)`` for each message on a topic, in order, one at a time.

    Messages wait in a queue of ``queue_size``; when the callback falls behind, the oldest are
    dropped (ROS's queue_size), so a slow callback never slows the publisher or the socket.
    """

    def __init__(
        self, topic_name: str, msg_type: type[Message], callback: Callable[[Any], Any], queue_size: int
    ) -> None:
        self.topic_name = topic_name
        self.msg_type = msg_type
        self.callback = callback
        self.queue_size = queue_size
        self._queue: deque[Message] = deque(maxlen=queue_size)
        self._ready = asyncio.Event()
        self.dropped = 0

    def enqueue(self, msg: Message) -> None:
        """Queue a message for the callback (on the receive path: never blocks)."""
        if len(self._queue) == self._queue.maxlen:
            self.dropped += 1
        self._queue.append(msg)
        self._ready.set()

    async def run(self, logger: logging.Logger) -> None:
        """Deliver queued messages to the callback until cancelled."""
        queue = self._queue
        what = f"subscription callback of {self.topic_name}"
        while True:
            await self._ready.wait()
            self._ready.clear()
            while queue:
                await call_user(self.callback, queue.popleft(), logger=logger, what=what)
