"""A bounded per-connection queue of serialised frames: the publisher never waits for a reader.

Like ROS's ``queue_size``: when a reader falls behind, its oldest frames are dropped; the
publisher and every other reader go on at full speed. There is no backpressure by design. The
queue is bounded in frames (the reader's ``queue``) and in bytes (a reader of camera images
does not hold a hundred of them), and it says since when its writer has been unable to send,
which is how a stalled reader is found (``services.runtime.edge.pump``).
"""

from __future__ import annotations

import asyncio
from collections import deque
from collections.abc import Callable

from services.runtime.edge.encoding import Encoding

__all__ = ["DEFAULT_OUTBOX_BYTES", "Outbox"]

DEFAULT_OUTBOX_BYTES = 8 << 20
"""Frames a reader may have waiting, in bytes, beyond its newest one."""

Frame = str | bytes


class Outbox:
    """Frames waiting to be written to one connection, oldest dropped when full."""

    __slots__ = ("_bytes", "_frames", "_ready", "busy_since", "dropped", "encoding", "max_bytes", "max_frames", "send_now")

    def __init__(self, maxlen: int, encoding: Encoding = Encoding.JSON, max_bytes: int = DEFAULT_OUTBOX_BYTES) -> None:
        self._frames: deque[Frame] = deque()
        self._ready = asyncio.Event()
        self._bytes = 0
        self.max_frames = maxlen
        self.max_bytes = max_bytes
        self.encoding = encoding
        self.dropped = 0
        # Since when (monotonic seconds) a send to this connection has been waiting for the
        # socket; None while sends complete. A send that waits long: the reader stopped reading.
        self.busy_since: float | None = None
        # Set by the connection's writer while it is idle: sends a frame at once instead of
        # waking the writer (True), or declines (False) and the frame is queued.
        self.send_now: Callable[[Frame], bool] | None = None

    def push(self, frame: Frame) -> None:
        """Queue ``frame``; called on the publish path, so it never blocks."""
        frames = self._frames
        if not frames and self.send_now is not None and self.send_now(frame):
            return
        frames.append(frame)
        self._bytes += len(frame)
        if len(frames) > self.max_frames or (self._bytes > self.max_bytes and len(frames) > 1):
            self._drop_oldest()
        self._ready.set()

    def _drop_oldest(self) -> None:
        frames = self._frames
        while len(frames) > self.max_frames or (self._bytes > self.max_bytes and len(frames) > 1):
            self._bytes -= len(frames.popleft())
            self.dropped += 1

    @property
    def waiting(self) -> int:
        """Frames queued now."""
        return len(self._frames)

    async def drain(self) -> list[Frame]:
        """Wait until frames are queued, then take all of them (oldest first)."""
        await self._ready.wait()
        self._ready.clear()
        frames = list(self._frames)
        self._frames.clear()
        self._bytes = 0
        return frames

    async def latest(self) -> Frame:
        """Wait until a frame is queued, then take only the newest (for throttled readers)."""
        await self._ready.wait()
        self._ready.clear()
        frame = self._frames[-1]
        self._frames.clear()
        self._bytes = 0
        return frame

    async def oldest(self) -> Frame:
        """Wait until a frame is queued, then take the oldest (for paced readers that keep every
        frame their queue holds: rosbridge's ``throttle_rate`` with a ``queue_length``)."""
        await self._ready.wait()
        frame = self._frames.popleft()
        self._bytes -= len(frame)
        if not self._frames:
            self._ready.clear()
        return frame
