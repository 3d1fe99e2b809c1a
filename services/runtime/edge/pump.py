"""Pumping one accepted WebSocket: an outbox written to it, and the frames a client sends read
from it, until either side ends the connection. The one loop behind every topic socket.

A reader's outbox is written by its own task (or, while that task is idle, by ``publish()``
itself: see :class:`_EagerSend`), so a slow reader loses its own oldest frames and never slows
the publisher or other readers.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import Callable, Coroutine, Sequence
from typing import Any

from starlette.websockets import WebSocket, WebSocketDisconnect

from services.runtime.edge.frames import FrameRejected, close_with
from services.runtime.edge.options import StreamOptions
from services.runtime.edge.outbox import Outbox
from services.runtime.wire import Close

__all__ = ["Encode", "serve_stream", "write_outbox"]


async def serve_stream(
    websocket: WebSocket,
    outbox: Outbox | None,
    *,
    options: StreamOptions,
    initial_frame: str | None,
    on_frame: Callable[[str], None] | None,
) -> None:
    """Write ``outbox`` to the accepted ``websocket`` and hand client frames to ``on_frame``.

    ``outbox`` is None for a publish-only socket (nothing is written to it). ``on_frame``
    validates and publishes a frame, raising FrameRejected to close this socket; ``None`` means
    the stream is read-only. Returns when either side ends the connection.
    """
    reader = asyncio.create_task(_read_frames(websocket, on_frame))
    writer = None
    try:
        if outbox is not None:
            writer = asyncio.create_task(_write_frames(websocket, outbox, options, initial_frame))
        done, _ = await asyncio.wait({reader} if writer is None else {reader, writer}, return_when=asyncio.FIRST_COMPLETED)
        if writer is not None:
            writer.cancel()
        if reader in done and (rejected := reader.exception()) is not None:
            if isinstance(rejected, FrameRejected):
                await close_with(websocket, rejected.code, rejected.reason)
            else:
                raise rejected
    finally:
        reader.cancel()


_Send = Callable[[Any], Coroutine[Any, Any, None]]
ASGIMessage = dict[str, Any]
Encode = Callable[[str], Sequence[ASGIMessage]]
"""A protocol's form of one frame: the ASGI ``websocket.send`` messages that carry it."""


async def _write_frames(
    websocket: WebSocket, outbox: Outbox, options: StreamOptions, initial_frame: str | None
) -> None:
    await write_outbox(websocket.send, outbox, rate_hz=options.rate_hz, initial_frame=initial_frame)


async def write_outbox(
    send: _Send,
    outbox: Outbox,
    *,
    rate_hz: float | None = None,
    initial_frame: str | None = None,
    encode: Encode | None = None,
) -> None:
    """Write ``outbox`` with ``send`` (a WebSocket's ASGI send) until the socket is gone.

    Frames go as JSON text unless ``encode`` turns each into a protocol's messages (rosbridge's
    envelope, Foxglove's binary frame); a throttled reader (``rate_hz``) gets the newest frame
    each period. Protocol adapters run one of these per subscription on one socket: each write
    completes on its own, so frames of different subscriptions never interleave.
    """
    eager = _EagerSend(send, encode)
    try:
        with contextlib.suppress(WebSocketDisconnect, RuntimeError, OSError):
            if initial_frame is not None:
                await _send_frame(send, initial_frame, encode)
            if rate_hz is None:
                while True:
                    outbox.send_now = eager  # only while idle: a frame must not overtake queued ones
                    frames = await outbox.drain()
                    outbox.send_now = None
                    await eager.settled()
                    if encode is None:
                        for frame in frames:
                            await send({"type": "websocket.send", "text": frame})
                    else:
                        for frame in frames:
                            for message in encode(frame):
                                await send(message)
            else:
                period_s = 1.0 / rate_hz
                while True:
                    await _send_frame(send, await outbox.latest(), encode)
                    await asyncio.sleep(period_s)
    finally:
        outbox.send_now = None
        eager.cancel()


async def _send_frame(send: _Send, frame: str, encode: Encode | None) -> None:
    if encode is None:
        await send({"type": "websocket.send", "text": frame})
        return
    for message in encode(frame):
        await send(message)


class _EagerSend:
    """Sends a frame from ``publish()`` itself while the connection's writer is idle.

    Waking the writer task costs a turn of the event loop per message (a quarter of the
    publish-to-callback latency). A WebSocket send normally completes without suspending (the
    server writes to the transport), so its coroutine is stepped here, the way Python 3.12's
    eager tasks start: done in one step, nothing else happens. If it must wait (the transport
    paused writing), a task finishes it, and the writer waits for that task before sending more.
    A frame that a protocol sends as several messages (fragments) is left to the writer.
    """

    def __init__(self, send: _Send, encode: Encode | None = None) -> None:
        self._send = send
        self._encode = encode
        self._pending: asyncio.Task[None] | None = None

    def __call__(self, frame: str) -> bool:
        if self._pending is not None:
            return False  # an earlier frame still waits for the socket: queue behind it
        if self._encode is None:
            message: ASGIMessage = {"type": "websocket.send", "text": frame}
        else:
            messages = self._encode(frame)
            if len(messages) != 1:
                return False
            message = messages[0]
        step = self._send(message)
        try:
            waiting_on = step.send(None)
        except StopIteration:
            return True
        except Exception:
            return False  # the socket is gone: the writer meets the same error and ends the stream
        self._pending = asyncio.ensure_future(_finish(step, waiting_on))
        return True

    async def settled(self) -> None:
        """Wait for a send that had to wait for the socket (its error, if any, is raised here)."""
        if self._pending is not None:
            pending, self._pending = self._pending, None
            await pending

    def cancel(self) -> None:
        if self._pending is not None:
            self._pending.cancel()


async def _finish(step: Coroutine[Any, Any, None], waiting_on: Any) -> None:
    """Run a coroutine that suspended on its first step to the end (what a task would do)."""
    try:
        while True:
            try:
                if waiting_on is None:
                    await asyncio.sleep(0)  # a bare yield: resume on the next turn
                else:
                    await asyncio.wait([waiting_on])  # the coroutine reads its result itself
            except asyncio.CancelledError:
                step.close()
                raise
            waiting_on = step.send(None)
    except StopIteration:
        return


async def _read_frames(websocket: WebSocket, on_frame: Callable[[str], None] | None) -> None:
    while True:
        message = await websocket.receive()
        if message["type"] == "websocket.disconnect":
            return
        text = message.get("text")
        if text is None:
            raise FrameRejected(Close.UNSUPPORTED, "binary frames are not supported: send JSON text")
        if on_frame is None:
            raise FrameRejected(Close.UNSUPPORTED, "this stream is read-only")
        on_frame(text)
