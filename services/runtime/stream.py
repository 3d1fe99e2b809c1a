"""Serving one topic stream over a WebSocket: the edge where frames enter and leave a process.

Used by nodes (their own topics) and by the core's gateway alike. Each connection gets an
:class:`~services.runtime.outbox.Outbox` written by one task, while another reads the frames the
client publishes. Problems close only this socket, with a code and a reason:

- 1003 a binary frame (topics are JSON text)
- 1007 a frame that is not valid JSON of the topic's type (the reason names the field)
- 1008 bad query options (``queue``, ``rate``) or a missing/wrong token
- 1009 a frame over the size limit (enforced by the server's ``ws_max_size``)
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import Callable, Coroutine
from dataclasses import dataclass
from typing import Any, TypeVar

from pydantic import BaseModel, ValidationError
from starlette.websockets import WebSocket, WebSocketDisconnect, WebSocketState

from services.runtime.outbox import Outbox

__all__ = [
    "CLOSE_BAD_OPTION",
    "CLOSE_INVALID_FRAME",
    "CLOSE_TOO_BIG",
    "CLOSE_UNSUPPORTED",
    "FrameRejected",
    "StreamOptions",
    "describe_validation_error",
    "serve_stream",
]

CLOSE_UNSUPPORTED = 1003
CLOSE_INVALID_FRAME = 1007
CLOSE_BAD_OPTION = 1008
CLOSE_TOO_BIG = 1009

DEFAULT_QUEUE = 100
MAX_QUEUE = 10_000
MAX_RATE_HZ = 1_000.0
M = TypeVar("M", bound=BaseModel)

_MAX_REASON_BYTES = 123  # RFC 6455: a close frame's reason fits in 123 bytes


class FrameRejected(Exception):
    """A frame a client sent cannot be taken; closes that socket with ``code`` and ``reason``."""

    def __init__(self, code: int, reason: str) -> None:
        super().__init__(reason)
        self.code = code
        self.reason = reason


@dataclass(frozen=True)
class StreamOptions:
    """Per-connection options from the query string: ``?queue=N&rate=HZ``."""

    queue: int = DEFAULT_QUEUE
    rate_hz: float | None = None

    @classmethod
    def from_query(cls, query: dict[str, str]) -> StreamOptions:
        """Parse and check the options; raises FrameRejected(1008) naming the bad one."""
        queue = DEFAULT_QUEUE
        rate_hz = None
        if "queue" in query:
            try:
                queue = int(query["queue"])
            except ValueError:
                queue = 0
            if not 1 <= queue <= MAX_QUEUE:
                raise FrameRejected(CLOSE_BAD_OPTION, f"queue must be an integer 1..{MAX_QUEUE}")
        if "rate" in query:
            try:
                rate_hz = float(query["rate"])
            except ValueError:
                rate_hz = -1.0
            if not 0 < rate_hz <= MAX_RATE_HZ:
                raise FrameRejected(CLOSE_BAD_OPTION, f"rate must be a number in (0, {MAX_RATE_HZ:g}]")
        return cls(queue=queue, rate_hz=rate_hz)

    @property
    def outbox_size(self) -> int:
        """A throttled reader gets only the newest frame; others a queue of ``queue``."""
        return 1 if self.rate_hz else self.queue


def describe_validation_error(type_name: str, error: ValidationError) -> str:
    """One line naming the first bad field of a frame: ``invalid geometry_msgs/msg/Twist: ...``."""
    first = error.errors(include_url=False)[0]
    location = ".".join(str(part) for part in first["loc"]) or "(message)"
    more = f" (+{error.error_count() - 1} more)" if error.error_count() > 1 else ""
    return f"invalid {type_name}: {location}: {first['msg']}{more}"


def parse_frame(msg_type: type[M], type_name: str, text: str) -> M:
    """Validate one text frame against the topic's type, or raise FrameRejected(1007)."""
    try:
        return msg_type.model_validate_json(text)
    except ValidationError as error:
        raise FrameRejected(CLOSE_INVALID_FRAME, describe_validation_error(type_name, error)) from None


def _clip_reason(reason: str) -> str:
    data = reason.encode()
    if len(data) <= _MAX_REASON_BYTES:
        return reason
    return data[: _MAX_REASON_BYTES - 3].decode(errors="ignore") + "..."


async def close_with(websocket: WebSocket, code: int, reason: str) -> None:
    """Close ``websocket`` with ``code`` and a reason clipped to what a close frame can carry."""
    if websocket.application_state == WebSocketState.DISCONNECTED:
        return
    with contextlib.suppress(RuntimeError, OSError):
        await websocket.close(code=code, reason=_clip_reason(reason))


async def serve_stream(
    websocket: WebSocket,
    outbox: Outbox,
    *,
    options: StreamOptions,
    initial_frame: str | None,
    on_frame: Callable[[str], None] | None,
) -> None:
    """Write ``outbox`` to the accepted ``websocket`` and hand client frames to ``on_frame``.

    ``on_frame`` validates and publishes a frame, raising FrameRejected to close this socket;
    ``None`` means the stream is read-only. Returns when either side ends the connection.
    """
    reader = asyncio.create_task(_read_frames(websocket, on_frame))
    try:
        writer = asyncio.create_task(_write_frames(websocket, outbox, options, initial_frame))
        done, _ = await asyncio.wait({reader, writer}, return_when=asyncio.FIRST_COMPLETED)
        writer.cancel()
        if reader in done and (rejected := reader.exception()) is not None:
            if isinstance(rejected, FrameRejected):
                await close_with(websocket, rejected.code, rejected.reason)
            else:
                raise rejected
    finally:
        reader.cancel()


_Send = Callable[[Any], Coroutine[Any, Any, None]]


async def _write_frames(
    websocket: WebSocket, outbox: Outbox, options: StreamOptions, initial_frame: str | None
) -> None:
    send = websocket.send
    eager = _EagerSend(send)
    try:
        with contextlib.suppress(WebSocketDisconnect, RuntimeError, OSError):
            if initial_frame is not None:
                await send({"type": "websocket.send", "text": initial_frame})
            if options.rate_hz is None:
                while True:
                    outbox.send_now = eager  # only while idle: a frame must not overtake queued ones
                    frames = await outbox.drain()
                    outbox.send_now = None
                    await eager.settled()
                    for frame in frames:
                        await send({"type": "websocket.send", "text": frame})
            else:
                await _write_throttled(send, outbox, options.rate_hz)
    finally:
        outbox.send_now = None
        eager.cancel()


async def _write_throttled(send: _Send, outbox: Outbox, rate_hz: float) -> None:
    period_s = 1.0 / rate_hz
    while True:
        await send({"type": "websocket.send", "text": await outbox.latest()})
        await asyncio.sleep(period_s)


class _EagerSend:
    """Sends a frame from ``publish()`` itself while the connection's writer is idle.

    Waking the writer task costs a turn of the event loop per message (a quarter of the
    publish-to-callback latency). A WebSocket send normally completes without suspending (the
    server writes to the transport), so its coroutine is stepped here, the way Python 3.12's
    eager tasks start: done in one step, nothing else happens. If it must wait (the transport
    paused writing), a task finishes it, and the writer waits for that task before sending more.
    """

    def __init__(self, send: _Send) -> None:
        self._send = send
        self._pending: asyncio.Task[None] | None = None

    def __call__(self, frame: str) -> bool:
        if self._pending is not None:
            return False  # an earlier frame still waits for the socket: queue behind it
        step = self._send({"type": "websocket.send", "text": frame})
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
            raise FrameRejected(CLOSE_UNSUPPORTED, "binary frames are not supported: send JSON text")
        if on_frame is None:
            raise FrameRejected(CLOSE_UNSUPPORTED, "this stream is read-only")
        on_frame(text)
