"""The core's HTTP connections: plain service calls forwarded below ASGI, everything else uvicorn's.

A call through the gateway (``POST /NAME`` of a registered service) is the core's busiest HTTP
request, and the only one whose work is a byte copy: the body goes to the hosting node, the
node's reply comes back. Profiled, the core spent ~180 us of CPU per forwarded call, two thirds
of it in the layers every ASGI request meets (uvicorn's request cycle, scope and message dicts,
the middleware, Starlette's request and response objects) and which such a call does not use.
So the core's server speaks HTTP itself first (uvicorn's ``http=`` option takes a protocol class):

- A connection starts here. A request that is a plain service call (POST, HTTP/1.1 keep-alive,
  a registered service's name with no ``%``-escapes and no query, a ``Content-Length`` within the
  size limit, no ``Origin``, ``Expect`` or ``Transfer-Encoding``) is parsed by httptools and
  forwarded through :meth:`ServiceCalls.start`, the one call path every caller takes, so its
  checks, statuses and error details are those of the ASGI route's; the reply is written from
  the node reply's own I/O callback (no task, no turn of the loop: docs/performance.md).
- Any other request (a browser's, a WebSocket upgrade, a GET, a call with ``?token=``, anything
  unusual or malformed) hands the connection, with every byte of that request, to uvicorn's own
  httptools protocol, which serves it and the rest of the connection as it serves any app. The
  edge checks (origin, size) and FastAPI see it as before.

Requests on one connection are answered in order: one a client sends before the previous reply
(pipelining) waits, unread, until that reply is written. Idle connections close after uvicorn's
keep-alive timeout; at shutdown, idle ones close at once and busy ones after their reply.
"""

from __future__ import annotations

import asyncio
import logging
from http import HTTPStatus
from typing import TYPE_CHECKING, Any, Protocol, cast

import httptools
from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol

from services.core.service_calls import CallOutcome, ServiceCalls, ServiceReply
from services.runtime.auth import bearer_token

if TYPE_CHECKING:
    from uvicorn.config import Config
    from uvicorn.server import ServerState

__all__ = ["GatewayHttpProtocol"]

logger = logging.getLogger("skydeck.core")

# Request headers that take a call off the fast path (a browser's page, a streamed or held body).
_DECLINED_HEADERS = frozenset({b"origin", b"transfer-encoding", b"expect"})
_REASONS = {status.value: status.phrase.encode("ascii") for status in HTTPStatus}
_FAULT = ServiceReply(500, b"Internal Server Error", "text/plain; charset=utf-8")


class _ServesCalls(Protocol):
    """An app whose service calls the protocol forwards (the core's: CoreApp)."""

    service_calls: ServiceCalls | None  # None while the core is not running


class _Call:
    """The request being read: what the forward needs, and whether it may take the fast path."""

    __slots__ = ("authorization", "body", "calls", "complete", "content_length", "content_type", "fast", "name", "url")

    def __init__(self) -> None:
        self.url = b""
        self.name = ""  # the url decoded, once it is known to be a service's
        self.body = b""
        self.authorization = ""
        self.content_type: str | None = None
        self.content_length = 0
        self.fast = True  # until a header or the request line says otherwise
        self.calls: ServiceCalls | None = None  # who forwards it, once its headers say it is a call
        self.complete = False


class GatewayHttpProtocol(asyncio.Protocol):
    """One HTTP connection to the core (made by uvicorn, whose ``config.app`` is the CoreApp)."""

    # Set by connection_made, which asyncio calls before any other method.
    _transport: asyncio.Transport

    def __init__(
        self, config: Config, server_state: ServerState, app_state: dict[str, Any], _loop: Any = None
    ) -> None:
        self._config = config
        self._server_state = server_state
        self._app_state = app_state
        # Kept: on Python 3.11 each asyncio.get_running_loop() is a getpid() system call, and the
        # forward path would make several per call. uvicorn makes protocols in the loop's thread.
        self._loop: asyncio.AbstractEventLoop = _loop or asyncio.get_running_loop()
        app = config.app
        self._app = cast("_ServesCalls", app) if hasattr(app, "service_calls") else None
        self._max_bytes: int = getattr(app, "max_message_bytes", 0)
        self._parser = httptools.HttpRequestParser(self)
        self._received: list[bytes] = []  # every byte of the request being read (for a hand-off)
        self._received_bytes = 0
        self._call = _Call()
        self._calls_begun = 0  # in the bytes fed since the last reply: more than one is pipelining
        self._waiting: list[bytes] = []  # bytes that came while a call was forwarded
        self._forwarding = False
        self._closing = False
        self._idle_timer: asyncio.TimerHandle | None = None
        self._idle_since = 0.0
        self._default_headers_of: object = None  # uvicorn's list of them, and it as bytes
        self._default_headers_bytes = b""

    # -- asyncio.Protocol ----------------------------------------------------------------------

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        self._transport = transport  # type: ignore[assignment]
        self._server_state.connections.add(self)  # type: ignore[arg-type]
        if self._app is None:  # not the core's app: nothing to take here
            self._hand_off()
            return
        self._idle_since = self._loop.time()
        self._arm_idle_timer(self._config.timeout_keep_alive)

    def data_received(self, data: bytes) -> None:
        if self._forwarding:
            self._waiting.append(data)
            self._transport.pause_reading()  # read on after the reply
            return
        self._received.append(data)
        self._received_bytes += len(data)
        try:
            self._parser.feed_data(data)
        except (httptools.HttpParserError, httptools.HttpParserUpgrade):
            self._hand_off()  # uvicorn answers the malformed request, or upgrades the WebSocket
            return
        if self._calls_begun == 0:
            return  # not a byte of a request yet
        call = self._call
        if not call.fast or self._calls_begun > 1 or self._received_bytes > self._max_bytes + 65536:
            self._hand_off()
        elif call.complete and call.calls is not None:  # (a complete call still fast was taken)
            self._forward(call, call.calls)

    def connection_lost(self, exc: Exception | None) -> None:
        self._server_state.connections.discard(self)  # type: ignore[arg-type]
        self._cancel_idle_timer()

    def shutdown(self) -> None:
        """The server stops: an idle connection closes now, a busy one after its reply."""
        self._closing = True
        if not self._forwarding:
            self._transport.close()

    # -- httptools callbacks -------------------------------------------------------------------

    def on_message_begin(self) -> None:
        self._calls_begun += 1
        self._call = _Call()

    def on_url(self, url: bytes) -> None:
        self._call.url += url

    def on_header(self, name: bytes, value: bytes) -> None:
        call = self._call
        name = name.lower()
        if name == b"content-length":
            call.content_length = int(value) if value.isdigit() else -1
        elif name == b"content-type":
            call.content_type = value.decode("latin-1")
        elif name == b"authorization":
            call.authorization = value.decode("latin-1")
        elif name in _DECLINED_HEADERS:
            call.fast = False

    def on_headers_complete(self) -> None:
        call = self._call
        parser = self._parser
        calls = self._app.service_calls if self._app is not None else None
        if (
            calls is None
            or not call.fast
            or parser.get_method() != b"POST"
            or parser.get_http_version() != "1.1"
            or not parser.should_keep_alive()
            or not 0 <= call.content_length <= self._max_bytes
            or b"?" in call.url
            or b"%" in call.url
        ):
            call.fast = False
            return
        call.name = call.url.decode("latin-1")
        if calls.serves(call.name):
            call.calls = calls
        else:
            call.fast = False

    def on_body(self, body: bytes) -> None:
        if self._call.fast:
            self._call.body += body

    def on_message_complete(self) -> None:
        self._call.complete = True

    # -- the fast path -------------------------------------------------------------------------

    def _forward(self, call: _Call, calls: ServiceCalls) -> None:
        self._forwarding = True
        try:
            calls.start(
                call.name,
                call.body,
                caller=calls.fences.admit(bearer_token(call.authorization)),
                content_type=call.content_type,
                on_done=self._answer,
            )
        except Exception:  # a fault of ours: said in the log, as uvicorn says an app's
            logger.exception("forwarding a call to %s failed", call.name)
            self._closing = True
            self._answer(_FAULT)

    def _answer(self, outcome: CallOutcome) -> None:
        """The call's reply, from the node reply's I/O callback (or at once, for a refusal)."""
        if not self._forwarding:
            return  # answered already (a fault after the forward had begun)
        self._write(outcome if isinstance(outcome, ServiceReply) else outcome.reply())
        self._forwarding = False
        self._received.clear()
        self._received_bytes = 0
        self._calls_begun = 0
        transport = self._transport
        if transport.is_closing():
            return
        if self._closing:
            transport.close()
            return
        if self._waiting:  # a request sent before this reply: read it now
            waiting = b"".join(self._waiting)
            self._waiting.clear()
            transport.resume_reading()
            self.data_received(waiting)
        else:
            self._idle_since = self._loop.time()

    def _write(self, reply: ServiceReply) -> None:
        transport = self._transport
        if transport.is_closing():
            return  # the client left: the node's reply has nowhere to go
        content_type = b"content-type: %s\r\n" % reply.content_type.encode("latin-1") if reply.content_type else b""
        transport.write(
            b"HTTP/1.1 %d %s\r\n%s%scontent-length: %d\r\n\r\n%s"
            % (reply.status, _REASONS.get(reply.status, b""), self._default_headers(), content_type, len(reply.body), reply.body)
        )

    def _default_headers(self) -> bytes:
        """uvicorn's headers for every reply (date, and server unless turned off), as bytes: the
        list is replaced, not changed, when the date does (once a second), so it is kept by identity."""
        headers = self._server_state.default_headers
        if headers is not self._default_headers_of:
            self._default_headers_of = headers
            self._default_headers_bytes = b"".join(b"%s: %s\r\n" % pair for pair in headers)
        return self._default_headers_bytes

    # -- everything else: uvicorn's protocol ---------------------------------------------------

    def _hand_off(self) -> None:
        """Give the connection, with the bytes of the request being read, to uvicorn's protocol."""
        transport = self._transport
        self._cancel_idle_timer()
        self._server_state.connections.discard(self)  # type: ignore[arg-type]
        uvicorn_protocol = HttpToolsProtocol(
            config=self._config, server_state=self._server_state, app_state=self._app_state, _loop=self._loop
        )
        transport.set_protocol(uvicorn_protocol)
        uvicorn_protocol.connection_made(transport)
        received = b"".join(self._received)
        self._received.clear()
        self._received_bytes = 0
        if received and not transport.is_closing():
            uvicorn_protocol.data_received(received)

    # One timer per connection, not one per call: it looks at how long the connection has been
    # idle when it fires, and closes it or waits for the rest of the keep-alive timeout.
    def _arm_idle_timer(self, delay_s: float) -> None:
        self._idle_timer = self._loop.call_later(delay_s, self._idle)

    def _cancel_idle_timer(self) -> None:
        if self._idle_timer is not None:
            self._idle_timer.cancel()
            self._idle_timer = None

    def _idle(self) -> None:
        timeout_s = self._config.timeout_keep_alive
        if self._forwarding or self._received:  # busy: not idle at all
            self._arm_idle_timer(timeout_s)
            return
        left_s = timeout_s - (self._loop.time() - self._idle_since)
        if left_s > 0:
            self._arm_idle_timer(left_s)
            return
        self._idle_timer = None
        self._transport.close()
