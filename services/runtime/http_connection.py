"""One keep-alive HTTP/1.1 connection of Skydeck's HTTP client (:mod:`services.runtime.http_client`)
and what a request on it comes to: a reply (:class:`HttpReply`, of any status) or why none came
(:class:`HttpError`: :class:`HttpTimeout`, :class:`HttpUnreachable`)."""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import httptools

from shared_models.errors import SkydeckError

__all__ = ["MAX_REPLY_BYTES", "MAX_IDLE_S", "Connection", "HttpError", "HttpReply", "HttpTimeout", "HttpUnreachable", "Outcome"]

# uvicorn closes a keep-alive connection after 5 idle seconds; reusing one older than this
# would race that close.
MAX_IDLE_S = 4.0
MAX_REPLY_BYTES = 64 * 1024 * 1024


class HttpError(SkydeckError):
    """A request that got no reply."""


class HttpTimeout(HttpError):
    """No complete reply within the timeout."""


class HttpUnreachable(HttpError):
    """The server could not be reached, or the connection broke before the reply."""


@dataclass(frozen=True, slots=True)
class HttpReply:
    """A reply of any status: status, headers (lower-case names) and body."""

    status: int
    headers: dict[str, str]  # lower-case names
    body: bytes

    @property
    def text(self) -> str:
        return self.body.decode("utf-8", errors="replace")

    def json(self) -> Any:
        return json.loads(self.body)


Outcome = HttpReply | HttpError
"""What a request came to: the reply (of any status), or why none came."""


class Connection(asyncio.Protocol):
    """One keep-alive connection; parses one reply at a time and hands it on from its I/O callback."""

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        # The loop it was made on, kept: on Python 3.11 every asyncio.get_running_loop() is a
        # getpid() system call, six of them per forwarded call before this.
        self._loop = loop
        # One timer per connection, not one per request: it looks at the request waiting when it
        # fires and times it out, or waits on for its deadline.
        self._timer: asyncio.TimerHandle | None = None
        self._deadline = 0.0
        self.transport: asyncio.Transport | None = None
        self.idle_since = 0.0
        self.received_any = False
        self._parser = httptools.HttpResponseParser(self)
        self._headers: dict[str, str] = {}
        self._body: list[bytes] = []
        self._size = 0
        self._on_done: Callable[[Connection, Outcome], None] | None = None  # while a request awaits its reply
        self._closed = False

    # -- asyncio.Protocol -------------------------------------------------------------------

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        self.transport = transport  # type: ignore[assignment]

    def data_received(self, data: bytes) -> None:
        self.received_any = True
        if self._on_done is None:  # bytes nobody asked for: the connection cannot be trusted
            self.close()
            return
        try:
            self._parser.feed_data(data)
        except httptools.HttpParserError as error:
            self._fail(HttpUnreachable(f"malformed reply: {error}"))

    def connection_lost(self, exc: Exception | None) -> None:
        self._closed = True
        self._fail(HttpUnreachable("the server closed the connection before replying"))

    # -- httptools callbacks -----------------------------------------------------------------

    def on_header(self, name: bytes, value: bytes) -> None:
        self._headers[name.decode("latin-1").lower()] = value.decode("latin-1")

    def on_body(self, body: bytes) -> None:
        self._size += len(body)
        if self._size > MAX_REPLY_BYTES:
            self._fail(HttpUnreachable(f"reply larger than {MAX_REPLY_BYTES} bytes"))
            return
        self._body.append(body)

    def on_message_complete(self) -> None:
        reply = HttpReply(self._parser.get_status_code(), self._headers, b"".join(self._body))
        self.idle_since = time.monotonic()
        if not self._parser.should_keep_alive():
            self.close()
        self._finish(reply)

    # -- use ---------------------------------------------------------------------------------

    @property
    def usable(self) -> bool:
        return (
            not self._closed
            and self.transport is not None
            and not self.transport.is_closing()
            and time.monotonic() - self.idle_since < MAX_IDLE_S
        )

    def send(self, request: bytes, timeout_s: float, on_done: Callable[[Connection, Outcome], None]) -> None:
        """Write ``request``; ``on_done`` gets its reply, or :class:`HttpTimeout` if no whole reply
        comes within ``timeout_s``, or :class:`HttpUnreachable`."""
        self._headers = {}  # the parser goes on from the last reply (keep-alive)
        self._body = []
        self._size = 0
        self.received_any = False
        self._on_done = on_done
        self._deadline = self._loop.time() + max(timeout_s, 0.0)
        if self._timer is None or self._timer.when() > self._deadline:
            self._arm_timer()
        if self.transport is None:  # only connected ones are pooled or made: said, should it happen
            self._fail(HttpUnreachable("the connection was never made"))
            return
        self.transport.write(request)

    def close(self) -> None:
        self._closed = True
        self._stop_timer()
        if self.transport is not None:
            self.transport.close()

    def _arm_timer(self) -> None:
        self._stop_timer()
        self._timer = self._loop.call_at(self._deadline, self._time_out)

    def _time_out(self) -> None:
        self._timer = None
        if self._on_done is None:
            return  # no request waits: the next one arms the timer again
        if self._loop.time() < self._deadline:
            self._arm_timer()  # a later request's: wait on
            return
        self._fail(HttpTimeout())

    def _stop_timer(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None

    def _fail(self, error: HttpError) -> None:
        self.close()
        self._finish(error)

    def _finish(self, outcome: Outcome) -> None:
        on_done, self._on_done = self._on_done, None
        if on_done is not None:
            on_done(self, outcome)  # an _Exchange's, which guards its caller's callback
