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

Errors: :class:`HttpTimeout` (no complete reply in time) and :class:`HttpUnreachable` (no
connection, or it broke), both :class:`HttpError`. A reply of any status is a reply.
"""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

import httptools

from shared_models.errors import SkydeckError

__all__ = ["HttpClient", "HttpError", "HttpReply", "HttpTimeout", "HttpUnreachable"]

# uvicorn closes a keep-alive connection after 5 idle seconds; reusing one older than this
# would race that close.
_MAX_IDLE_S = 4.0
_MAX_IDLE_PER_ORIGIN = 8
MAX_REPLY_BYTES = 64 * 1024 * 1024
_MAX_KNOWN_URLS = 1024


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


class _Connection(asyncio.Protocol):
    """One keep-alive connection; parses one reply at a time."""

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        # The loop it was made on, kept: on Python 3.11 every asyncio.get_running_loop() is a
        # getpid() system call, six of them per forwarded call before this.
        self._loop = loop
        self._timer: asyncio.TimerHandle | None = None
        self.transport: asyncio.Transport | None = None
        self.idle_since = 0.0
        self.received_any = False
        self._parser = httptools.HttpResponseParser(self)
        self._headers: dict[str, str] = {}
        self._body: list[bytes] = []
        self._size = 0
        self._reply: asyncio.Future[HttpReply] | None = None
        self._closed = False

    # -- asyncio.Protocol -------------------------------------------------------------------

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        self.transport = transport  # type: ignore[assignment]

    def data_received(self, data: bytes) -> None:
        self.received_any = True
        if self._reply is None:  # bytes nobody asked for: the connection cannot be trusted
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
        self._stop_timer()
        if not self._parser.should_keep_alive():
            self.close()
        if self._reply is not None and not self._reply.done():
            self._reply.set_result(reply)

    # -- use ---------------------------------------------------------------------------------

    @property
    def usable(self) -> bool:
        return (
            not self._closed
            and self.transport is not None
            and not self.transport.is_closing()
            and time.monotonic() - self.idle_since < _MAX_IDLE_S
        )

    def send(self, request: bytes, timeout_s: float) -> asyncio.Future[HttpReply]:
        """Write ``request``; the future fails with :class:`HttpTimeout` if no whole reply comes
        within ``timeout_s`` (one timer on the loop, not an ``asyncio.timeout`` per call)."""
        assert self.transport is not None  # the parser goes on from the last reply (keep-alive)
        self._headers = {}
        self._body = []
        self._size = 0
        self.received_any = False
        self._reply = self._loop.create_future()
        self._timer = self._loop.call_later(max(timeout_s, 0.0), self._time_out)
        self.transport.write(request)
        return self._reply

    def release(self) -> None:
        self._reply = None
        self.idle_since = time.monotonic()

    def close(self) -> None:
        self._closed = True
        self._stop_timer()
        if self.transport is not None:
            self.transport.close()

    def _time_out(self) -> None:
        self._timer = None
        self._fail(HttpTimeout())

    def _stop_timer(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None

    def _fail(self, error: HttpError) -> None:
        self.close()
        if self._reply is not None and not self._reply.done():
            self._reply.set_exception(error)


class HttpClient:
    """Pooled keep-alive HTTP/1.1 to ``http://`` URLs; ``headers`` go with every request."""

    def __init__(self, headers: Mapping[str, str] | None = None) -> None:
        self._default_headers = "".join(f"{name}: {value}\r\n" for name, value in (headers or {}).items())
        self._idle: dict[tuple[str, int], list[_Connection]] = {}
        self._request_lines: dict[tuple[str, str], tuple[tuple[str, int], str]] = {}
        self._closed = False

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
        if self._closed:
            raise HttpUnreachable("the HTTP client is closed")
        origin, request_line = self._request_line(method, url)
        payload = body.encode() if isinstance(body, str) else body
        extra = headers or {}
        if any("\r" in text or "\n" in text for item in extra.items() for text in item):
            raise ValueError("an HTTP header name or value holds a line break")
        if method == "POST" and not any(name.lower() == "content-type" for name in extra):
            extra = {**extra, "Content-Type": "application/json"}
        head = (
            request_line
            + "".join(f"{name}: {value}\r\n" for name, value in extra.items())
            + f"Content-Length: {len(payload)}\r\n\r\n"
        )
        request = head.encode("latin-1") + payload
        try:
            return await self._exchange(origin, request, time.monotonic() + timeout_s)
        except (HttpTimeout, TimeoutError):
            raise HttpTimeout(f"no reply from {url} within {timeout_s:g} s") from None

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

    async def _exchange(self, origin: tuple[str, int], request: bytes, deadline: float) -> HttpReply:
        while True:
            connection, reused = await self._connection(origin, deadline)
            try:
                reply = await connection.send(request, deadline - time.monotonic())
            except HttpUnreachable:
                # A kept-alive connection the server dropped while idle: it never saw the
                # request, so sending it again on a new connection cannot run it twice.
                if reused and not connection.received_any:
                    continue
                raise
            except BaseException:  # timeout or cancellation mid-reply: the connection is spoilt
                connection.close()
                raise
            connection.release()
            if connection.usable:
                pool = self._idle.setdefault(origin, [])
                if len(pool) < _MAX_IDLE_PER_ORIGIN:
                    pool.append(connection)
                else:
                    connection.close()
            return reply

    async def _connection(self, origin: tuple[str, int], deadline: float) -> tuple[_Connection, bool]:
        pool = self._idle.get(origin)
        while pool:
            connection = pool.pop()
            if connection.usable:
                return connection, True
            connection.close()
        loop = asyncio.get_running_loop()
        try:
            async with asyncio.timeout(deadline - time.monotonic()):
                _, connection = await loop.create_connection(lambda: _Connection(loop), *origin)
        except OSError as error:
            raise HttpUnreachable(f"cannot connect to {origin[0]}:{origin[1]}: {error.strerror or error}") from None
        return connection, False

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
