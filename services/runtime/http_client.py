"""The HTTP client Skydeck processes use among themselves: keep-alive HTTP/1.1 over asyncio.

Service calls between nodes, the core's gateway and the launch supervisor's health checks all
talk plain ``http://`` to other Skydeck processes, on loopback or a container network. httpx did
this job first; profiling the gateway showed its layers (auth, redirects, cookies, anyio, a
failed ``import sniffio`` per request) took 60% of the core's CPU per forwarded call. This client
does only what those calls need: one pooled connection per request in flight, requests written
in one piece, responses parsed by httptools (llhttp, the parser uvicorn already uses).
No proxies from the environment either: a loopback call must never go through ``HTTP_PROXY``.

    client = HttpClient()
    reply = await client.request("POST", "http://127.0.0.1:8003/control/take_off", b"{}", timeout_s=5)
    reply.status, reply.json()
    await client.aclose()

:meth:`HttpClient.start` is the same request with its outcome handed to a callback, called from
the reply's own I/O callback when a kept-alive connection was free: no task, no future, no turn of
the loop between the reply and its use. The core's gateway forwards calls that way (about a
quarter of its time per call went to those turns and the coroutines around them); ``request`` is ``start``
and a future.

Errors: :class:`HttpTimeout` (no complete reply in time) and :class:`HttpUnreachable` (no
connection, or it broke), both :class:`HttpError`. A reply of any status is a reply.
"""

from __future__ import annotations

import asyncio
import json
import logging
import time
from collections.abc import Callable, Coroutine, Mapping
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

import httptools

from services.runtime.lockstep.activity import ACTIVITY
from shared_models.errors import SkydeckError

__all__ = ["HttpClient", "HttpError", "HttpReply", "HttpTimeout", "HttpUnreachable", "Outcome"]

# uvicorn closes a keep-alive connection after 5 idle seconds; reusing one older than this
# would race that close.
_MAX_IDLE_S = 4.0
_MAX_IDLE_PER_ORIGIN = 8
MAX_REPLY_BYTES = 64 * 1024 * 1024
_MAX_KNOWN_URLS = 1024

logger = logging.getLogger("skydeck.runtime")


class HttpError(SkydeckError):
    """A request that got no reply."""


class HttpTimeout(HttpError):
    """No complete reply within the timeout."""


class HttpUnreachable(HttpError):
    """The server could not be reached, or the connection broke before the reply."""


@dataclass(frozen=True, slots=True)
class HttpReply:
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


class _Connection(asyncio.Protocol):
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
        self._on_done: Callable[[Outcome], None] | None = None  # while a request awaits its reply
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
            and time.monotonic() - self.idle_since < _MAX_IDLE_S
        )

    def send(self, request: bytes, timeout_s: float, on_done: Callable[[Outcome], None]) -> None:
        """Write ``request``; ``on_done`` gets its reply, or :class:`HttpTimeout` if no whole reply
        comes within ``timeout_s``, or :class:`HttpUnreachable`."""
        assert self.transport is not None  # the parser goes on from the last reply (keep-alive)
        self._headers = {}
        self._body = []
        self._size = 0
        self.received_any = False
        self._on_done = on_done
        self._deadline = self._loop.time() + max(timeout_s, 0.0)
        if self._timer is None or self._timer.when() > self._deadline:
            self._arm_timer()
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
            on_done(outcome)  # an _Exchange's, which guards its caller's callback


class _Exchange:
    """One request and its way to an outcome: on a kept-alive connection, else on a new one; a
    kept-alive connection the server dropped while idle is tried again on a new one (it never saw
    the request, so it cannot run twice)."""

    __slots__ = (
        "_client", "_connecting", "_connection", "_deadline", "_on_done", "_origin", "_request", "_reused", "_timeout_s", "_url"
    )  # fmt: skip

    def __init__(
        self,
        client: HttpClient,
        origin: tuple[str, int],
        request: bytes,
        url: str,
        timeout_s: float,
        on_done: Callable[[Outcome], None],
    ) -> None:
        self._client = client
        self._origin = origin
        self._request = request
        self._url = url
        self._timeout_s = timeout_s
        self._deadline = time.monotonic() + timeout_s
        self._on_done = on_done
        self._connection: _Connection | None = None
        self._reused = False
        self._connecting: asyncio.Task[None] | None = None

    def start(self) -> None:
        connection = self._client._pooled(self._origin)
        if connection is None:
            self._connecting = self._client._in_task(self._connect())
        else:
            self._send_on(connection, reused=True)

    def abort(self) -> None:
        """The caller gave up (cancelled): a reply that still comes has nowhere to go."""
        self._on_done = _ignore
        if self._connecting is not None:
            self._connecting.cancel()
        if self._connection is not None:
            self._connection.close()  # spoilt: its reply would be read as the next request's

    async def _connect(self) -> None:
        loop = asyncio.get_running_loop()
        try:
            async with asyncio.timeout(self._deadline - time.monotonic()):
                _, connection = await loop.create_connection(lambda: _Connection(loop), *self._origin)
        except TimeoutError:
            self._deliver(self._timed_out())
            return
        except OSError as error:
            where = f"{self._origin[0]}:{self._origin[1]}"
            self._deliver(HttpUnreachable(f"cannot connect to {where}: {error.strerror or error}"))
            return
        self._connecting = None
        self._send_on(connection, reused=False)

    def _send_on(self, connection: _Connection, *, reused: bool) -> None:
        self._connection = connection
        self._reused = reused
        connection.send(self._request, self._deadline - time.monotonic(), self._done)

    def _done(self, outcome: Outcome) -> None:
        connection = self._connection
        assert connection is not None
        self._connection = None
        if isinstance(outcome, HttpReply):
            self._client._keep(self._origin, connection)
        elif isinstance(outcome, HttpTimeout):
            outcome = self._timed_out()  # the connection's says nothing of which request
        elif self._reused and not connection.received_any:
            self.start()  # a kept-alive connection dropped while idle: again, on another
            return
        self._deliver(outcome)

    def _timed_out(self) -> HttpTimeout:
        return HttpTimeout(f"no reply from {self._url} within {self._timeout_s:g} s")

    def _deliver(self, outcome: Outcome) -> None:
        try:
            self._on_done(outcome)
        except Exception:  # a fault of the caller's callback: said, not left in a task or a reader
            logger.exception("handling a reply of the HTTP client failed")


def _ignore(outcome: Outcome) -> None:
    pass


class HttpClient:
    """Pooled keep-alive HTTP/1.1 to ``http://`` URLs; ``headers`` go with every request."""

    def __init__(self, headers: Mapping[str, str] | None = None) -> None:
        self._default_headers = "".join(f"{name}: {value}\r\n" for name, value in (headers or {}).items())
        self._idle: dict[tuple[str, int], list[_Connection]] = {}
        self._request_lines: dict[tuple[str, str], tuple[tuple[str, int], str]] = {}
        self._closed = False
        self._tasks: set[asyncio.Task[None]] = set()  # connecting: held here, the loop holds tasks weakly

    async def get(self, url: str, *, timeout_s: float) -> HttpReply:
        return await self.request("GET", url, timeout_s=timeout_s)

    async def post(
        self, url: str, body: bytes | str, *, timeout_s: float, headers: Mapping[str, str] | None = None
    ) -> HttpReply:
        return await self.request("POST", url, body, timeout_s=timeout_s, headers=headers)

    async def request(
        self,
        method: str,
        url: str,
        body: bytes | str = b"",
        *,
        timeout_s: float,
        headers: Mapping[str, str] | None = None,
    ) -> HttpReply:
        """Send one request and return the whole reply (any status)."""
        outcome: asyncio.Future[Outcome] = asyncio.get_running_loop().create_future()

        def done(result: Outcome) -> None:
            if not outcome.done():
                outcome.set_result(result)

        exchange = self.start(method, url, body, timeout_s=timeout_s, headers=headers, on_done=done)
        try:
            with ACTIVITY.working():  # a lockstep run waits for the reply (services.runtime.lockstep)
                result = await outcome
        except BaseException:  # cancelled while the request was out
            exchange.abort()
            raise
        if isinstance(result, HttpError):
            raise result
        return result

    def start(
        self,
        method: str,
        url: str,
        body: bytes | str = b"",
        *,
        timeout_s: float,
        on_done: Callable[[Outcome], None],
        headers: Mapping[str, str] | None = None,
    ) -> _Exchange:
        """Send one request; ``on_done`` gets its reply (any status) or the :class:`HttpError` of
        why none came, once. Called from the reply's own I/O callback when a kept-alive connection
        was free: no task and no turn of the loop between the reply and its use, which is what
        the core's gateway needs of a forwarded call. Raises ValueError for a header with a line
        break and HttpUnreachable for a URL this client does not reach, before sending anything.
        """
        if self._closed:
            raise HttpUnreachable("the HTTP client is closed")
        origin, request_line = self._request_line(method, url)
        payload = body.encode() if isinstance(body, str) else body
        extra = headers or {}
        lines = "".join([f"{name}: {value}\r\n" for name, value in extra.items()])
        # One line break per header, each its own: any other is in a name or value.
        if lines.count("\n") != len(extra) or lines.count("\r") != len(extra):
            raise ValueError("an HTTP header name or value holds a line break")
        if method == "POST" and "\ncontent-type:" not in ("\n" + lines).lower():
            lines += "Content-Type: application/json\r\n"
        head = request_line + lines + f"Content-Length: {len(payload)}\r\n\r\n"
        exchange = _Exchange(self, origin, head.encode("latin-1") + payload, url, timeout_s, on_done)
        exchange.start()
        return exchange

    def _request_line(self, method: str, url: str) -> tuple[tuple[str, int], str]:
        """Where ``url`` is, and the request's first lines up to its own headers (kept per URL:
        parsing a URL is a tenth of a forwarded call's work, and the core calls few URLs)."""
        known = self._request_lines.get((method, url))
        if known is None:
            origin, target = _split(url)
            host = f"[{origin[0]}]" if ":" in origin[0] else origin[0]
            known = origin, f"{method} {target} HTTP/1.1\r\nHost: {host}:{origin[1]}\r\n{self._default_headers}"
            if len(self._request_lines) >= _MAX_KNOWN_URLS:
                self._request_lines.clear()
            self._request_lines[(method, url)] = known
        return known

    def _pooled(self, origin: tuple[str, int]) -> _Connection | None:
        pool = self._idle.get(origin)
        while pool:
            connection = pool.pop()
            if connection.usable:
                return connection
            connection.close()
        return None

    def _in_task(self, coroutine: Coroutine[Any, Any, None]) -> asyncio.Task[None]:
        task = asyncio.get_running_loop().create_task(coroutine)
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)
        return task

    def _keep(self, origin: tuple[str, int], connection: _Connection) -> None:
        if self._closed or not connection.usable:
            connection.close()
            return
        pool = self._idle.setdefault(origin, [])
        if len(pool) < _MAX_IDLE_PER_ORIGIN:
            pool.append(connection)
        else:
            connection.close()

    async def aclose(self) -> None:
        self._closed = True
        for pool in self._idle.values():
            for connection in pool:
                connection.close()
        self._idle.clear()


def _split(url: str) -> tuple[tuple[str, int], str]:
    parts = urlsplit(url)
    if parts.scheme != "http" or not parts.hostname:
        raise HttpUnreachable(f"{url}: only http:// URLs are reached by Skydeck's internal client")
    target = parts.path or "/"
    if parts.query:
        target += "?" + parts.query
    return (parts.hostname, parts.port or 80), target
