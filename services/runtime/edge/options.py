"""A topic socket's options, from its query string: ``?queue=N&rate=HZ&mode=publish&batch=1``
(and ``&reader=/NODE``: a node in a lockstep run, :mod:`services.runtime.lockstep`)."""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass

from services.runtime.edge.frames import FrameRejected
from services.runtime.wire import DEFAULT_QUEUE, MAX_QUEUE, MAX_RATE_HZ, Close
from shared_models.names import InvalidNameError, resolve_name

__all__ = ["Mode", "StreamOptions"]


class Mode(enum.Enum):
    """What a socket does on its topic (``?mode=``)."""

    BOTH = "both"  # reads the topic and may publish on it (the default)
    SUBSCRIBE = "subscribe"  # reads only; a frame sent on it closes it with 1003
    PUBLISH = "publish"  # publishes only: nothing is sent to it, so a publisher pays for no reading


@dataclass(frozen=True)
class StreamOptions:
    """Per-connection options; every one has a default, so a bare URL works."""

    queue: int = DEFAULT_QUEUE
    rate_hz: float | None = None
    mode: Mode = Mode.BOTH
    batch: bool = False  # a frame may carry several messages (services.runtime.edge.batch)
    reader: str = ""  # the reading node, when it is in a lockstep run: what is sent to it is counted

    @classmethod
    def from_query(cls, query: Mapping[str, str]) -> StreamOptions:
        """Parse and check the options; raises FrameRejected(1008) naming the bad one."""
        queue = DEFAULT_QUEUE
        rate_hz = None
        mode = Mode.BOTH
        if "queue" in query:
            try:
                queue = int(query["queue"])
            except ValueError:
                queue = 0
            if not 1 <= queue <= MAX_QUEUE:
                raise FrameRejected(Close.POLICY, f"queue must be an integer 1..{MAX_QUEUE}")
        if "rate" in query:
            try:
                rate_hz = float(query["rate"])
            except ValueError:
                rate_hz = -1.0
            if not 0 < rate_hz <= MAX_RATE_HZ:
                raise FrameRejected(Close.POLICY, f"rate must be a number in (0, {MAX_RATE_HZ:g}]")
        if "mode" in query:
            try:
                mode = Mode(query["mode"])
            except ValueError:
                choices = ", ".join(m.value for m in Mode)
                raise FrameRejected(Close.POLICY, f"mode must be one of {choices}") from None
        batch = query.get("batch", "0")
        if batch not in ("0", "1"):
            raise FrameRejected(Close.POLICY, "batch must be 0 or 1")
        reader = query.get("reader", "")
        if reader:
            try:
                reader = resolve_name(reader)
            except InvalidNameError as error:
                raise FrameRejected(Close.POLICY, f"reader must be a node name: {error}") from None
        return cls(queue=queue, rate_hz=rate_hz, mode=mode, batch=batch == "1", reader=reader)

    @property
    def reads(self) -> bool:
        """Whether frames of the topic are sent to this socket."""
        return self.mode is not Mode.PUBLISH

    @property
    def outbox_size(self) -> int:
        """A throttled reader gets only the newest frame; others a queue of ``queue``."""
        return 1 if self.rate_hz else self.queue
