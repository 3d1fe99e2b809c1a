"""The HTTP client Skydeck processes use among themselves: keep-alive HTTP/1.1 over asyncio.

Service calls between nodes, the core's gateway and the launch supervisor's health checks talk
plain ``http://`` to other Skydeck processes, on loopback or a container network; the CLI talks
to a core that may be anywhere (``https://`` behind a TLS proxy: docs/security.md), one request
at a time (:func:`request_once`). httpx did this job first; profiling the gateway showed its
layers (auth, redirects, cookies, anyio, a failed ``import sniffio`` per request) took 60% of the
core's CPU per forwarded call, and its import a quarter of a CLI command's start-up
(docs/architecture.md has the figures). This client does only what those calls need: one pooled
connection per request in flight, requests written in one piece, responses parsed by httptools
(llhttp, the parser uvicorn already uses). No proxies from the environment either: a call to a
node or a core on the robot's network must never go through ``HTTP_PROXY``.

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
connection, or it broke), both :class:`HttpError`. A reply of any status is a reply. One
connection and what it yields (replies, errors) are :mod:`services.runtime.http_connection`'s.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import logging
import ssl
import time
from collections.abc import Callable, Coroutine, Mapping
from typing import Any, NamedTuple, Protocol, TypeVar
from urllib.parse import urlsplit

from services.runtime.http_connection import (
    MAX_REPLY_BYTES,
    Connection,
    HttpError,
    HttpReply,
    HttpTimeout,
    HttpUnreachable,
    Outcome,
)
from services.runtime.lockstep.activity import ACTIVITY

__all__ = [
    "MAX_REPLY_BYTES", "Cancellable", "HttpClient", "HttpError", "HttpReply", "HttpTimeout", "HttpUnreachable",
    "Outcome", "outcome_of", "request_once",
]  # fmt: skip

_MAX_IDLE_PER_ORIGIN = 8
_MAX_KNOWN_URLS = 1024

logger = logging.getLogger("skydeck.runtime")


class _Origin(NamedTuple):
    """Where a request goes: connections are pooled per origin."""

    host: str
    port: int
    tls: bool  # https://

T = TypeVar("T")


class Cancellable(Protocol):
    """An operation under way that its caller may give up (an exchange, a task)."""

    def cancel(self) -> object: ...


async def outcome_of(start: Callable[[Callable[[T], None]], Cancellable | None]) -> T:
    """The outcome a callback-form operation hands its callback, awaited.

    ``start(on_done)`` begins the operation; ``on_done`` may be called at once or later, and only
    the first outcome counts. Cancelled while waiting, the operation is cancelled too.
    """
    future: asyncio.Future[T] = asyncio.get_running_loop().create_future()

    def done(outcome: T) -> None:
        if not future.done():
            future.set_result(outcome)

    operation = start(done)
    try:
        return await future
    except BaseException:  # cancelled while the operation was out
        if operation is not None:
            operation.cancel()
        raise


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
        origin: _Origin,
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
        self._connection: Connection | None = None
        self._reused = False
        self._connecting: asyncio.Task[None] | None = None

    def start(self) -> None:
        connection = self._client._pooled(self._origin)
        if connection is None:
            self._connecting = self._client._in_task(self._connect())
        else:
            self._send_on(connection, reused=True)

    def cancel(self) -> None:
        """The caller gave up: a reply that still comes has nowhere to go."""
        self._on_done = _ignore
        if self._connecting is not None:
            self._connecting.cancel()
        if self._connection is not None:
            self._connection.close()  # spoilt: its reply would be read as the next request's

    async def _connect(self) -> None:
        loop = asyncio.get_running_loop()
        origin = self._origin
        try:
            async with asyncio.timeout(self._deadline - time.monotonic()):
                _, connection = await loop.create_connection(
                    lambda: Connection(loop), origin.host, origin.port, **self._client._tls_options(origin)
                )
        except TimeoutError:
            self._deliver(self._timed_out())
            return
        except OSError as error:  # ssl.SSLError (a certificate refused) is one
            where = f"{origin.host}:{origin.port}"
            self._deliver(HttpUnreachable(f"cannot connect to {where}: {error.strerror or error}"))
            return
        self._connecting = None
        self._send_on(connection, reused=False)

    def _send_on(self, connection: Connection, *, reused: bool) -> None:
        self._connection = connection
        self._reused = reused
        connection.send(self._request, self._deadline - time.monotonic(), self._done)

    def _done(self, connection: Connection, outcome: Outcome) -> None:
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
    """Pooled keep-alive HTTP/1.1 to ``http://`` and ``https://`` URLs; ``headers`` go with every
    request, ``tls`` checks the servers' certificates (default: the system's, as ``ssl`` does)."""

    def __init__(self, headers: Mapping[str, str] | None = None, *, tls: ssl.SSLContext | None = None) -> None:
        self._tls = tls  # https://'s, made on first use: the system's certificates (ssl's default)
        self._default_headers = "".join(f"{name}: {value}\r\n" for name, value in (headers or {}).items())
        self._idle: dict[_Origin, list[Connection]] = {}
        self._request_lines: dict[tuple[str, str], tuple[_Origin, str]] = {}
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
        with ACTIVITY.working():  # a lockstep run waits for the reply (services.runtime.lockstep)
            outcome: Outcome = await outcome_of(
                lambda on_done: self.start(method, url, body, timeout_s=timeout_s, headers=headers, on_done=on_done)
            )
        if isinstance(outcome, HttpError):
            raise outcome
        return outcome

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

    def _request_line(self, method: str, url: str) -> tuple[_Origin, str]:
        """Where ``url`` is, and the request's first lines up to its own headers (kept per URL:
        parsing a URL is a tenth of a forwarded call's work, and the core calls few URLs)."""
        known = self._request_lines.get((method, url))
        if known is None:
            origin, target = _split(url)
            host = f"[{origin.host}]" if ":" in origin.host else origin.host
            known = origin, f"{method} {target} HTTP/1.1\r\nHost: {host}:{origin.port}\r\n{self._default_headers}"
            if len(self._request_lines) >= _MAX_KNOWN_URLS:
                self._request_lines.clear()
            self._request_lines[(method, url)] = known
        return known

    def _tls_options(self, origin: _Origin) -> dict[str, Any]:
        if not origin.tls:
            return {}
        if self._tls is None:
            self._tls = ssl.create_default_context()
        return {"ssl": self._tls, "server_hostname": origin.host}

    def _pooled(self, origin: _Origin) -> Connection | None:
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

    def _keep(self, origin: _Origin, connection: Connection) -> None:
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


def request_once(
    method: str, url: str, body: bytes | str = b"", *, timeout_s: float, headers: Mapping[str, str] | None = None
) -> HttpReply:
    """One request from blocking code (a CLI command, a launch before its loop, a harness polling
    a process): on a loop and a connection of its own. Raises as ``request``."""

    async def once() -> HttpReply:
        client = HttpClient()
        try:
            return await client.request(method, url, body, timeout_s=timeout_s, headers=headers)
        finally:
            await client.aclose()

    try:
        asyncio.get_running_loop()
    except RuntimeError:
        return asyncio.run(once())
    # Blocking code called from a coroutine (a test's harness): the loop of this thread is busy
    # until the call returns, as with any blocking call, so the request runs in a thread of its own.
    with concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="request_once") as pool:
        return pool.submit(asyncio.run, once()).result()


def _split(url: str) -> tuple[_Origin, str]:
    parts = urlsplit(url)
    if parts.scheme not in ("http", "https") or not parts.hostname:
        raise HttpUnreachable(f"{url}: Skydeck's HTTP client reaches http:// and https:// URLs only")
    target = parts.path or "/"
    if parts.query:
        target += "?" + parts.query
    tls = parts.scheme == "https"
    return _Origin(parts.hostname, parts.port or (443 if tls else 80), tls), target
