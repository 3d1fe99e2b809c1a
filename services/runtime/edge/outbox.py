"""A bounded per-connection queue of serialised frames: the publisher never waits for a reader.

Like ROS's ``queue_size``: when a reader falls behind, its oldest frames are dropped; the
publisher and every other reader go on at full speed. There is no backpressure by design. The
queue is bounded in frames (the reader's ``queue``) and in bytes (a reader of camera images
does not hold a hundred of them), and it says since when its writer has been unable to send,
which is how a stalled reader is found (``services.runtime.edge.pump``). A reader that asked
for batches (:mod:`.batch`) gets the first frame published in a turn of the event loop at once,
as every reader does, and the rest of that turn's, or those queued while its socket was busy,
joined into one frame.
"""

from __future__ import annotations

import asyncio
from collections import deque
from collections.abc import Callable

from services.runtime.edge.batch import BATCH_MAX_BYTES, join, one_line
from services.runtime.edge.encoding import Encoding

__all__ = ["DEFAULT_OUTBOX_BYTES", "Outbox"]

DEFAULT_OUTBOX_BYTES = 8 << 20
"""Frames a reader may have waiting, in bytes, beyond its newest one."""

Frame = str | bytes


class Outbox:
    """Frames waiting to be written to one connection, oldest dropped when full."""

    __slots__ = (
        "_bytes", "_flush_pending", "_frames", "_ready", "batch", "busy_since", "dropped", "encoding",
        "max_bytes", "max_frames", "send_now",
    )  # fmt: skip

    def __init__(
        self, maxlen: int, encoding: Encoding = Encoding.JSON, max_bytes: int = DEFAULT_OUTBOX_BYTES, *, batch: bool = False
    ) -> None:
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
        # A batching outbox sends the first frame of a loop turn at once
        # and joins the rest of that turn's into one frame at its end.
        self.batch = batch
        self._flush_pending = False

    def sendable(self, frame: Frame) -> Frame:
        """``frame`` as this reader is sent it: on one line for a batching JSON reader."""
        return one_line(frame) if self.batch else frame

    def push(self, frame: Frame) -> None:
        """Queue ``frame``; called on the publish path, so it never blocks."""
        frames = self._frames
        frame = self.sendable(frame)
        if not frames and not self._flush_pending and self.send_now is not None and self.send_now(frame):
            if self.batch:  # the first frame of a loop turn went at once; the rest go at its end
                self._flush_at_turn_end()
            return
        # A batch that is full goes now, as unbatched frames would have: only a reader whose
        # socket cannot take it loses frames, never one that a long turn filled up.
        if self.batch and frames and self._bytes + len(frame) > BATCH_MAX_BYTES:
            self._send_queued()
        frames.append(frame)
        self._bytes += len(frame)
        if self.batch and len(frames) >= self.max_frames:
            self._send_queued()
        if len(frames) > self.max_frames or (self._bytes > self.max_bytes and len(frames) > 1):
            self._drop_oldest()
        if self.batch:
            self._flush_at_turn_end()
        else:
            self._ready.set()

    def _flush_at_turn_end(self) -> None:
        if not self._flush_pending:
            self._flush_pending = True
            asyncio.get_running_loop().call_soon(self._flush)

    def _flush(self) -> None:
        """End of the loop turn: what a batching outbox holds goes as one frame, else (the
        writer busy, or more than one frame's worth) the writer takes it."""
        self._flush_pending = False
        if self._frames and not self._send_queued():
            self._ready.set()

    def _send_queued(self) -> bool:
        """Send the queued frames as one, from here, if the writer is idle and they fit one."""
        frames = self._frames
        fits_one = len(frames) == 1 or self._bytes <= BATCH_MAX_BYTES
        if fits_one and self.send_now is not None and self.send_now(join(list(frames))[0]):
            frames.clear()
            self._bytes = 0
            return True
        return False

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
        """Wait until frames are queued, then take all of them (oldest first; a batching outbox
        joins them into as few frames as :mod:`.batch` allows)."""
        await self._ready.wait()
        self._ready.clear()
        frames = list(self._frames)
        self._frames.clear()
        self._bytes = 0
        if self.batch and len(frames) > 1:
            return join(frames)
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
