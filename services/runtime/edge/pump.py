"""Pumping one accepted WebSocket: an outbox written to it, and the frames a client sends read
from it, until either side ends the connection. The one loop behind every topic socket.

A reader's outbox is written by its own task (or, while that task is idle, by ``publish()``
itself: see :class:`_EagerSend`), so a slow reader loses its own oldest frames and never slows
the publisher or other readers. A reader whose socket has taken nothing for ``stall_timeout_s``
while frames wait has stopped reading: it is closed with 4001 (``Close.STALLED``), which it
sees after the frames it already has, with a proper closing handshake (not a reset).
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import Callable, Coroutine, Sequence
from typing import Any, cast

from starlette.websockets import WebSocket, WebSocketDisconnect

from services.runtime.edge.encoding import Encoding
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.options import StreamOptions
from services.runtime.edge.outbox import Frame, Outbox
from services.runtime.wire import STALL_CHECK_PERIOD_S, Close

__all__ = ["Encode", "serve_stream", "watch_stall", "write_outbox"]


async def serve_stream(
    websocket: WebSocket,
    outbox: Outbox | None,
    *,
    options: StreamOptions,
    encoding: Encoding,
    initial_frame: Frame | None,
    on_frame: Callable[[Frame], None] | None,
    stall_timeout_s: float,
) -> FrameRejected | None:
    """Write ``outbox`` to the accepted ``websocket`` and hand client frames to ``on_frame``.

    ``outbox`` is None for a publish-only socket (nothing is written to it). ``on_frame``
    validates and publishes a frame, raising FrameRejected to end the stream; ``None`` means
    the stream is read-only. Returns when either side ends the connection, with the reason to
    close it if this side ended it (the caller detaches the socket first, then closes it).
    """
    reader = asyncio.create_task(_read_frames(websocket, on_frame, encoding))
    tasks = {reader}
    if outbox is not None:
        tasks.add(asyncio.create_task(_write_frames(websocket, outbox, options, initial_frame)))
        tasks.add(asyncio.create_task(_watch_stall(outbox, stall_timeout_s)))
    try:
        done, _ = await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
        for task in tasks - {reader}:
            task.cancel()
        rejected = done.pop().exception()
        if rejected is None or isinstance(rejected, FrameRejected):
            return rejected
        raise rejected
    finally:
        reader.cancel()


_Send = Callable[[Any], Coroutine[Any, Any, None]]
ASGIMessage = dict[str, Any]
Encode = Callable[[str], Sequence[ASGIMessage]]
"""A protocol's form of one JSON frame: the ASGI ``websocket.send`` messages that carry it."""
_Forms = Callable[[Frame], Sequence[ASGIMessage]]


def _message(frame: Frame) -> ASGIMessage:
    if isinstance(frame, str):
        return {"type": "websocket.send", "text": frame}
    return {"type": "websocket.send", "bytes": frame}


def _messages(frame: Frame) -> Sequence[ASGIMessage]:
    return (_message(frame),)


async def _write_frames(websocket: WebSocket, outbox: Outbox, options: StreamOptions, initial_frame: Frame | None) -> None:
    await write_outbox(websocket.send, outbox, rate_hz=options.rate_hz, spaced=False, initial_frame=initial_frame)


async def write_outbox(
    send: _Send,
    outbox: Outbox,
    *,
    rate_hz: float | None = None,
    paced_queue: bool = False,
    spaced: bool = True,
    initial_frame: Frame | None = None,
    encode: Encode | None = None,
) -> None:
    """Write ``outbox`` with ``send`` (a WebSocket's ASGI send) until the socket is gone.

    Frames go as they are (text or binary) unless ``encode`` turns each into a protocol's
    messages (rosbridge's envelope, Foxglove's binary frame); a throttled reader (``rate_hz``)
    gets the newest frame each period, or with ``paced_queue`` the oldest frame its outbox holds
    (rosbridge's ``throttle_rate`` with a ``queue_length``). ``spaced``: a period passes between
    two frames (rosbridge's ``throttle_rate``, the least time between messages); else at most
    ``rate_hz`` frames a second (the native socket's ``?rate=``): each frame is due a period after
    the one before was due, so a reader asking near a topic's own rate gets it, not every other
    frame. Protocol adapters run one of these per subscription on
    one socket: each write completes on its own, so frames of different subscriptions never
    interleave. ``outbox.busy_since`` is set while a send waits for the socket (the stall watch).
    """
    # A protocol's reader has a JSON outbox (its frames are text), as its encoder expects.
    forms: _Forms = _messages if encode is None else cast(_Forms, encode)
    eager = _EagerSend(send, outbox, forms)
    try:
        with contextlib.suppress(WebSocketDisconnect, RuntimeError, OSError):
            if initial_frame is not None:
                await _timed(send, outbox, outbox.sendable(initial_frame), forms)
            if rate_hz is None:
                while True:
                    outbox.send_now = eager  # only while idle: a frame must not overtake queued ones
                    frames = await outbox.drain()
                    outbox.send_now = None
                    await eager.settled()
                    for frame in frames:
                        await _timed(send, outbox, frame, forms)
            else:
                period_s = 1.0 / rate_hz
                take = outbox.oldest if paced_queue else outbox.latest
                clock = asyncio.get_running_loop().time
                due = clock()
                while True:
                    await _timed(send, outbox, await take(), forms)
                    # Due times a period apart at least, and never before the last send: at most
                    # one period's worth of frames a period, however late one came.
                    due = clock() + period_s if spaced else max(due + period_s, clock())
                    delay = due - clock()
                    if delay > 0:
                        await asyncio.sleep(delay)
    finally:
        outbox.send_now = None
        eager.cancel()


async def _timed(send: _Send, outbox: Outbox, frame: Frame, forms: _Forms) -> None:
    """One frame's sends, with ``outbox.busy_since`` set while they wait for the socket."""
    outbox.busy_since = time.monotonic()
    for message in forms(frame):
        await send(message)
    outbox.busy_since = None


async def _watch_stall(outbox: Outbox, stall_timeout_s: float) -> None:
    await watch_stall(lambda: outbox.busy_since, lambda: outbox.dropped, stall_timeout_s, "ask for less (?rate=HZ)")


async def watch_stall(
    waiting_since: Callable[[], float | None], dropped: Callable[[], int], stall_timeout_s: float, advice: str
) -> None:
    """Raise FrameRejected(4001) once the oldest send still waiting for the socket
    (``waiting_since()``, monotonic seconds; None: none waits) has waited ``stall_timeout_s``.

    Runs beside a connection's writers; the caller detaches the connection, then closes it.
    """
    while True:
        await asyncio.sleep(STALL_CHECK_PERIOD_S)
        since = waiting_since()
        if since is not None and time.monotonic() - since > stall_timeout_s:
            raise FrameRejected(
                Close.STALLED,
                f"reader stalled: read nothing for {stall_timeout_s:g} s ({dropped()} frames dropped); "
                f"reconnect, or {advice}",
            )


class _EagerSend:
    """Sends a frame from ``publish()`` itself while the connection's writer is idle.

    Waking the writer task costs a turn of the event loop per message (a quarter of the
    publish-to-callback latency). A WebSocket send normally completes without suspending (the
    server writes to the transport), so its coroutine is stepped here, the way Python 3.12's
    eager tasks start: done in one step, nothing else happens. If it must wait (the transport
    paused writing), a task finishes it, and the writer waits for that task before sending more.
    A frame that a protocol sends as several messages (fragments) is left to the writer.
    """

    def __init__(self, send: _Send, outbox: Outbox, forms: _Forms) -> None:
        self._send = send
        self._outbox = outbox
        self._forms = forms
        self._pending: asyncio.Task[None] | None = None

    def __call__(self, frame: Frame) -> bool:
        if self._pending is not None:
            return False  # an earlier frame still waits for the socket: queue behind it
        messages = self._forms(frame)
        if len(messages) != 1:
            return False
        step = self._send(messages[0])
        try:
            waiting_on = step.send(None)
        except StopIteration:
            return True
        except Exception:
            return False  # the socket is gone: the writer meets the same error and ends the stream
        self._outbox.busy_since = time.monotonic()
        self._pending = asyncio.ensure_future(_finish(step, waiting_on, self._outbox))
        return True

    async def settled(self) -> None:
        """Wait for a send that had to wait for the socket (its error, if any, is raised here)."""
        if self._pending is not None:
            pending, self._pending = self._pending, None
            await pending

    def cancel(self) -> None:
        if self._pending is not None:
            self._pending.cancel()


async def _finish(step: Coroutine[Any, Any, None], waiting_on: Any, outbox: Outbox) -> None:
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
        outbox.busy_since = None
        return


async def _read_frames(websocket: WebSocket, on_frame: Callable[[Frame], None] | None, encoding: Encoding) -> None:
    binary = encoding is not Encoding.JSON
    while True:
        message = await websocket.receive()
        if message["type"] == "websocket.disconnect":
            return
        frame = message.get("bytes") if binary else message.get("text")
        if frame is None:
            if binary:
                raise FrameRejected(Close.UNSUPPORTED, f"this socket speaks {encoding.value}: send binary frames")
            raise FrameRejected(Close.UNSUPPORTED, "binary frames need ?encoding=msgpack: send JSON text")
        if on_frame is None:
            raise FrameRejected(Close.UNSUPPORTED, "this stream is read-only")
        on_frame(frame)
