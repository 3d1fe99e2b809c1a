"""What a recorder records: the topics it picks from the graph as they appear, and their frames.

The same logic serves ``skydeck bag record`` (a node of its own) and the dashboard's recorder
(run by the core): each host shows it the graph's topics (``update``) and gives it a way to
subscribe to a topic's raw frames; every frame goes to the writer as received, with the time
it arrived.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from services.bag.errors import BagError
from services.bag.schemas import message_type
from services.bag.writer import BagWriter
from shared_models import Message

__all__ = ["Limits", "Recording", "TopicSelection"]

Subscribe = Callable[[str, type[Message], Callable[[str], None]], Any]
"""Subscribe to a topic's raw frames: ``subscribe(topic, msg_type, on_frame)``."""


@dataclass(frozen=True)
class TopicSelection:
    """Which topics to record: every one (``-a``) or the named ones, less those ``exclude`` matches."""

    all_topics: bool = False
    topics: frozenset[str] = frozenset()
    exclude: re.Pattern[str] | None = None

    def __post_init__(self) -> None:
        if not self.all_topics and not self.topics:
            raise BagError("name the topics to record, or -a for all of them")

    def wants(self, topic: str) -> bool:
        if self.exclude is not None and self.exclude.search(topic):
            return False
        return self.all_topics or topic in self.topics


@dataclass(frozen=True)
class Limits:
    """When a recording stops by itself: after ``duration_s`` of wall time (its host keeps that
    time), or at ``size_bytes`` on disk (checked as each chunk is written, at least every second)."""

    duration_s: float | None = None
    size_bytes: int | None = None


class Recording:
    """One recording in progress: its writer, the topics it has, and why it stopped (if it did)."""

    def __init__(
        self,
        writer: BagWriter,
        selection: TopicSelection,
        subscribe: Subscribe,
        *,
        limits: Limits = Limits(),
        say: Callable[[str], None] = lambda _: None,
    ) -> None:
        self.writer = writer
        self.selection = selection
        self.limits = limits
        self.started_s = time.monotonic()
        self.stop_reason: str | None = None
        self._subscribe = subscribe
        self._say = say
        self._skipped: set[str] = set()

    @property
    def topics(self) -> list[str]:
        return list(self.writer.counts())

    def update(self, graph_topics: Iterable[Mapping[str, Any]]) -> None:
        """Subscribe to every wanted topic of the graph not recorded yet (types known only)."""
        recorded = self.writer.counts()
        for topic in graph_topics:
            name, type_name = topic["name"], topic.get("type") or ""
            if name in recorded or name in self._skipped or not type_name or not self.selection.wants(name):
                continue
            try:
                msg_type = message_type(type_name)
                channel = self.writer.add_topic(name, type_name, latched=bool(topic.get("latched")))
            except BagError as error:
                self._skipped.add(name)
                self._say(f"not recording {name}: {error}")
                continue
            self._subscribe(name, msg_type, self._writes_to(channel))
            self._say(f"subscribed to {name} [{type_name}]")

    def missing(self) -> list[str]:
        """Named topics not recorded yet (not in the graph, or with no type known)."""
        return sorted(self.selection.topics - set(self.writer.counts()))

    def _writes_to(self, channel: int) -> Callable[[str], None]:
        write = self.writer.write
        clock = time.time_ns

        def on_frame(frame: str) -> None:
            write(channel, frame, clock())

        return on_frame

    def check_limits(self) -> str | None:
        """Flush the chunk in progress and say why to stop, if a limit is reached."""
        self.writer.flush()
        if self.limits.size_bytes is not None and self.writer.size_bytes >= self.limits.size_bytes:
            self.stop_reason = f"--max-size {self.limits.size_bytes / 1e6:g} MB reached"
        return self.stop_reason
