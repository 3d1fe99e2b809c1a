"""Subscriptions: ``node.create_subscription(PointStamped, "/my_point", callback, 10)``."""

from __future__ import annotations

import asyncio
import inspect
import logging
import time
from collections import deque
from collections.abc import Awaitable, Callable
from typing import Any

from services.runtime.callbacks import call_user
from services.runtime.edge.encoding import Encoding
from services.runtime.edge.outbox import Outbox
from shared_models import Message

__all__ = ["RawSubscription", "Subscription"]

# A plain callback that takes less than this on average keeps up with any burst a socket hands
# over (one read holds hundreds of frames): when its queue is full, the oldest message goes to
# the callback at once instead of being dropped. Slower callbacks keep ROS's drop-oldest, which
# keeps them on the newest messages.
_QUICK_CALLBACK_S = 0.001
_MEAN_WEIGHT = 0.1  # of the newest duration in the running mean


class Subscription:
    """Calls ``callback(msg)`` for each message on a topic, in order, one at a time.

    Messages wait in a queue of ``queue_size``; when the callback falls behind, the oldest are
    dropped (ROS's queue_size), so a slow callback never slows the publisher or the socket.
    A burst that only overflows the queue because it arrived in one piece is not "falling
    behind": a plain (non-async) callback that is quick gets every message of it.
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
        self._what = f"subscription callback of {topic_name}"
        self._logger = logging.getLogger("skydeck.runtime")  # the node's, once running
        # Only plain callbacks are ever called from receive; one found returning awaitables
        # (a lambda around a coroutine function) is treated as a coroutine callback from then on.
        self._plain = not inspect.iscoroutinefunction(callback)
        self._mean_call_s: float | None = None
        self._calling = False
        self._awaiting = 0  # coroutine callbacks started and not yet finished

    def receive(self, msg: Message) -> None:
        """A message from a socket; a quick plain callback may be called right here.

        With nothing queued, the message goes straight to it: that saves the hand-over to the
        delivery task (a task switch per message, ~15% of a receive) and keeps the order. When a
        burst (one socket read holds hundreds of frames) fills the queue, the oldest goes to it
        instead of being dropped. Only from sockets: a local publish never runs a callback
        inside ``publish()``, where two callbacks publishing to each other would recurse.
        """
        if self._plain and not self._calling and (self._mean_call_s or 0.0) < _QUICK_CALLBACK_S:
            queue = self._queue
            if not queue:
                self._call_inline(msg)
                return
            if len(queue) == queue.maxlen:
                self._call_inline(queue.popleft())
        self.enqueue(msg)

    def enqueue(self, msg: Message) -> None:
        """Queue a message for the delivery task; when the queue is full the oldest is dropped."""
        queue = self._queue
        if len(queue) == queue.maxlen:
            self.dropped += 1
        queue.append(msg)
        self._ready.set()

    def _call_inline(self, msg: Message) -> None:
        pending = self._call_now(msg)
        if pending is not None:
            self._awaiting += 1
            asyncio.ensure_future(self._finish(pending))

    @property
    def idle(self) -> bool:
        """Nothing queued and no callback running (what a lockstep run waits for)."""
        return not self._queue and not self._calling and not self._awaiting

    async def run(self, logger: logging.Logger) -> None:
        """Deliver queued messages to the callback until cancelled."""
        self._logger = logger
        queue = self._queue
        while True:
            await self._ready.wait()
            self._ready.clear()
            while queue:
                msg = queue.popleft()
                self._awaiting += 1
                if not self._plain:
                    try:
                        await call_user(self.callback, msg, logger=logger, what=self._what)
                    finally:
                        self._awaiting -= 1
                    continue
                pending = self._call_now(msg)
                if pending is None:
                    self._awaiting -= 1
                else:
                    await self._finish(pending)

    async def _finish(self, pending: Awaitable[Any]) -> None:
        """Await what a callback returned; ends one of ``_awaiting``."""
        try:
            await pending
        except Exception:
            self._logger.exception("%s raised; the node keeps running", self._what)
        finally:
            self._awaiting -= 1

    def _call_now(self, msg: Message) -> Awaitable[Any] | None:
        """Call the callback, timed; returns what it returned if that must still be awaited."""
        self._calling = True
        started = time.perf_counter()
        try:
            result = self.callback(msg)
        except Exception:
            self._logger.exception("%s raised; the node keeps running", self._what)
            result = None
        finally:
            self._calling = False
        elapsed = time.perf_counter() - started
        mean = self._mean_call_s
        self._mean_call_s = elapsed if mean is None else mean + (elapsed - mean) * _MEAN_WEIGHT
        if result is not None and inspect.isawaitable(result):
            self._plain = False
            return result
        return None


class RawSubscription(Outbox):
    """Calls ``callback(frame)`` with each frame of a topic as received, never parsed
    (rclpy's ``raw=True``): what a recorder needs, serialised once by the publisher.

    It is a tap on the topic's endpoint, so it sees every frame the participant gets: from each
    remote publisher, from clients of this node, and its own publications, as JSON text (a topic
    read only raw links in JSON, so nothing is converted), or, with ``encoding`` MSGPACK, as the
    msgpack bytes links carry between nodes (byte arrays as bytes: what the ROS 2 bridge reads).
    The callback runs where the frame arrives, so it must be a quick plain function;
    ``queue_size`` is the depth each publisher keeps for this participant while it reads.
    """

    def __init__(
        self,
        topic_name: str,
        msg_type: type[Message],
        callback: Callable[[Any], Any],
        queue_size: int,
        encoding: Encoding = Encoding.JSON,
    ) -> None:
        if inspect.iscoroutinefunction(callback):
            raise TypeError(f"a raw subscription's callback runs where each frame arrives: give {topic_name} a plain function")
        super().__init__(1, encoding)
        self.topic_name = topic_name
        self.msg_type = msg_type
        self.callback = callback
        self.queue_size = queue_size
        self._logger = logging.getLogger("skydeck.runtime")

    def push(self, frame: str | bytes) -> None:
        if self.encoding is Encoding.JSON and not isinstance(frame, str):  # endpoints hand JSON taps text
            raise TypeError(f"raw subscription of {self.topic_name} got a binary frame")
        try:
            self.callback(frame)
        except Exception:
            self._logger.exception("raw subscription callback of %s raised; the node keeps running", self.topic_name)
