"""``skydeck bag record``: a node that records topics into an MCAP file (rosbag record).

    recorder = Recorder(writer, TopicSelection(all_topics=True))
    asyncio.run(recorder.run_until_stopped())   # Ctrl-C, a limit, or destroy_node()
    writer.close()

It subscribes to each topic with ``raw=True``, so frames go to the file as the publisher
serialised them, and asks the core for the graph a few times a second, so topics that appear
later are recorded too (with ``-a``, or when a named topic shows up).
"""

from __future__ import annotations

import asyncio
import logging
import os
from collections.abc import Callable

from services.bag.recording import Limits, Recording, TopicSelection
from services.bag.writer import BagWriter
from services.runtime.core_types import interface_path, is_known, learn_definitions_reply
from services.runtime.http_client import HttpError
from services.runtime.node import Node
from services.runtime.settings import NodeSettings
from shared_models import Message

__all__ = ["DISCOVERY_PERIOD_S", "Recorder"]

DISCOVERY_PERIOD_S = 0.2
FLUSH_PERIOD_S = 1.0
RECORD_QUEUE_SIZE = 10_000
"""Frames each publisher keeps for the recorder while it writes (a burst at ``--speed max``)."""

logger = logging.getLogger("skydeck.bag")


class Recorder(Node):
    """Records the topics ``selection`` picks into ``writer`` until stopped or a limit is hit."""

    def __init__(
        self,
        writer: BagWriter,
        selection: TopicSelection,
        *,
        limits: Limits | None = None,
        settings: NodeSettings | None = None,
        say: Callable[[str], None] = lambda _: None,
    ) -> None:
        super().__init__(f"bag_record_{os.getpid()}", settings=settings)
        self.recording = Recording(writer, selection, self._subscribe_raw, limits=limits or Limits(), say=say)
        self._say = say
        self._said_missing = False
        self._types_checked: set[str] = set()  # known here, or asked of the core once
        self.create_timer(DISCOVERY_PERIOD_S, self._discover, wall_clock=True)
        self.create_timer(FLUSH_PERIOD_S, self._check_limits, wall_clock=True)

    async def start(self) -> None:
        await super().start()
        await self._discover()
        duration_s = self.recording.limits.duration_s
        if duration_s is not None:
            asyncio.get_running_loop().call_later(duration_s, self._stop_at_duration)

    def _stop_at_duration(self) -> None:
        self._say(f"stopping: --max-duration {self.recording.limits.duration_s:g} s reached")
        self.destroy_node()

    def _subscribe_raw(self, topic: str, msg_type: type[Message], on_frame: Callable[[str], None]) -> None:
        self.create_subscription(msg_type, topic, on_frame, RECORD_QUEUE_SIZE, raw=True)

    async def _discover(self) -> None:
        try:
            reply = await self.http.get(f"{self.settings.core_url}/api/graph", timeout_s=2.0)
        except HttpError as error:
            logger.debug("graph not read: %s", error)
            return
        if reply.status != 200:
            return
        topics = reply.json()["topics"]
        await self._learn_types({topic.get("type") or "" for topic in topics})
        self.recording.update(topics)
        missing = self.recording.missing()
        if missing and not self._said_missing:
            self._say(f"waiting for {', '.join(missing)} to appear")
            self._said_missing = True

    async def _learn_types(self, type_names: set[str]) -> None:
        """Types a node of the workspace declared (its own msg files) are asked of the core."""
        for type_name in sorted(type_names - self._types_checked):
            if not type_name or is_known(type_name):
                self._types_checked.add(type_name)
                continue
            try:
                reply = await self.http.get(self.settings.core_url + interface_path(type_name), timeout_s=2.0)
            except HttpError as error:
                logger.debug("type %s not asked: %s", type_name, error)
                continue
            self._types_checked.add(type_name)
            learn_definitions_reply(reply.status, reply.json() if reply.status == 200 else None)

    def _check_limits(self) -> None:
        reason = self.recording.check_limits()
        if reason is not None:
            self._say(f"stopping: {reason}")
            self.destroy_node()
