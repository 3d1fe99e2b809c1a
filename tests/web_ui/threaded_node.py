"""A real SDK node on its own event loop in a thread, for browser tests that publish on cue.

Playwright's sync API owns the test's thread; the node lives beside it and publishes when the
test says so (``publish``), or keeps publishing until the page shows what the test waits for
(``publish_every``), as a student's node would.
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable, Coroutine
from typing import Any, TypeVar

from services.runtime import Node, NodeSettings
from shared_models import Message

T = TypeVar("T")


class ThreadedNode:
    """``ThreadedNode("markers_test", core_url)``: a registered node; ``close()`` stops it."""

    def __init__(self, name: str, core_url: str) -> None:
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, name=name, daemon=True)
        self._thread.start()
        self._publishers: dict[str, Any] = {}
        self._repeaters: dict[str, asyncio.Task[None]] = {}

        async def start() -> Node:
            node = Node(name, settings=NodeSettings(core_url=core_url, port=0))
            await node.start()
            return node

        self.node = self._run(start())

    def _run(self, coroutine: Coroutine[Any, Any, T], timeout_s: float = 15.0) -> T:
        return asyncio.run_coroutine_threadsafe(coroutine, self._loop).result(timeout_s)

    def _call(self, fn: Callable[[], T]) -> T:
        async def call() -> T:
            return fn()

        return self._run(call())

    def _publisher(self, topic: str, msg: Message) -> Any:
        if topic not in self._publishers:
            self._publishers[topic] = self._call(
                lambda: self.node.create_publisher(type(msg), topic, 100)
            )
        return self._publishers[topic]

    def publish(self, topic: str, msg: Message) -> None:
        """Publish ``msg`` once on ``topic`` (the publisher is made on first use)."""
        publisher = self._publisher(topic, msg)
        self._call(lambda: publisher.publish(msg))

    def publish_every(self, topic: str, make: Callable[[], Message], period_s: float) -> None:
        """Publish ``make()`` on ``topic`` every ``period_s`` until ``stop(topic)``."""
        self.stop(topic)
        publisher = self._publisher(topic, make())

        async def repeat() -> None:
            while True:
                publisher.publish(make())
                await asyncio.sleep(period_s)

        self._repeaters[topic] = self._call(lambda: self._loop.create_task(repeat()))

    def stop(self, topic: str) -> None:
        """Stop repeating on ``topic`` (nothing to do if it does not repeat)."""
        task = self._repeaters.pop(topic, None)
        if task is not None:
            self._call(task.cancel)

    def close(self) -> None:
        for topic in list(self._repeaters):
            self.stop(topic)
        self._run(self.node.stop())
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join(timeout=5)
        self._loop.close()
