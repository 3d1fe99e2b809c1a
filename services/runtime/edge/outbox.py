"""A bounded per-connection queue of serialised frames: the publisher never waits for a reader.

Like ROS's ``queue_size``: when a reader falls behind, its oldest frames are dropped; the
publisher and every other reader go on at full speed. There is no backpressure by design.
"""

from __future__ import annotations

import asyncio
from collections import deque
from collections.abc import Callable

__all__ = ["Outbox"]


class Outbox:
    """Frames waiting to be written to one connection, oldest dropped when full."""

    __slots__ = ("_frames", "_ready", "dropped", "send_now")

    def __init__(self, maxlen: int) -> None:
        self._frames: deque[str] = deque(maxlen=maxlen)
        self._ready = asyncio.Event()
        self.dropped = 0
        # Set by the connection's writer while it is idle: sends a frame at once instead of
        # waking the writer (True), or declines (False) and the frame is queued.
        self.send_now: Callable[[str], bool] | None = None

    def push(self, frame: str) -> None:
        """Queue ``frame``; called on the publish path, so it never blocks."""
        frames = self._frames
        if not frames and self.send_now is not None and self.send_now(frame):
            return
        if len(frames) == frames.maxlen:
            self.dropped += 1
        frames.append(frame)
        self._ready.set()

    async def drain(self) -> list[str]:
        """Wait until frames are queued, then take all of them (oldest first)."""
        await self._ready.wait()
        self._ready.clear()
        frames = list(self._frames)
        self._frames.clear()
        return frames

    async def latest(self) -> str:
        """Wait until a frame is queued, then take only the newest (for throttled readers)."""
        await self._ready.wait()
        self._ready.clear()
        frame = self._frames[-1]
        self._frames.clear()
        return frame
