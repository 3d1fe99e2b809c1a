"""The protocol endpoints' own ports: rosbridge on 9090 and Foxglove on 8765, in the core process.

Each is a small ASGI app (one WebSocket route, and a line of text for a browser that opens the
port) served by its own uvicorn server in the core's event loop, so every connection uses the
same core node, registry and call path as the core's own routes. The ports are bound before the
core starts serving (:func:`bind_endpoints`): a port in use is one clear error at start-up
(:class:`EndpointPortBusy`), not a traceback; 0 turns an endpoint off.

Unlike the core's own port, these accept pages of any origin: Foxglove's web app and roslibjs
pages are served from elsewhere, as with rosbridge_server and foxglove_bridge. The write token
(``SKYDECK_TOKEN``) guards publishing and calls here as everywhere.
"""

from __future__ import annotations

import asyncio
import contextlib
import errno
import socket
from collections.abc import Awaitable, Callable, Iterator
from dataclasses import dataclass

import uvicorn
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import PlainTextResponse
from starlette.routing import Route, WebSocketRoute
from starlette.websockets import WebSocket

from services.core.settings import CoreSettings
from shared_models.errors import SkydeckError

__all__ = ["ENDPOINTS", "EndpointPortBusy", "EndpointServers", "bind_endpoints"]


@dataclass(frozen=True)
class _Endpoint:
    name: str  # "rosbridge"
    setting: str  # the CoreSettings field of its port
    flag: str  # the command-line flag that sets it
    greeting: str  # what a browser opening the port over HTTP reads


ENDPOINTS = (
    _Endpoint(
        "rosbridge",
        "rosbridge_port",
        "--rosbridge-port",
        "Skydeck's rosbridge v2 endpoint: connect roslibjs or roslibpy here with a WebSocket "
        "(new ROSLIB.Ros({url: 'ws://HOST:PORT'})). See docs/protocols.md.\n",
    ),
    _Endpoint(
        "foxglove",
        "foxglove_port",
        "--foxglove-port",
        "Skydeck's Foxglove WebSocket endpoint: in Foxglove or Lichtblick, open a connection to "
        "ws://HOST:PORT. See docs/protocols.md.\n",
    ),
)


class EndpointPortBusy(SkydeckError):
    """A protocol endpoint's port is taken (or cannot be bound) at start-up."""


def bind_endpoints(settings: CoreSettings) -> dict[str, socket.socket]:
    """Listening sockets of the endpoints that are on, by name; EndpointPortBusy names the
    first that cannot listen (those already bound are closed again)."""
    bound: dict[str, socket.socket] = {}
    try:
        for endpoint in ENDPOINTS:
            port = getattr(settings, endpoint.setting)
            if port:
                bound[endpoint.name] = _listen(settings.host, port, endpoint)
    except BaseException:
        for sock in bound.values():
            sock.close()
        raise
    return bound


def _listen(host: str, port: int, endpoint: _Endpoint) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
        sock.listen(128)
    except OSError as error:
        sock.close()
        why = "is in use" if error.errno == errno.EADDRINUSE else f"cannot be used ({error.strerror})"
        raise EndpointPortBusy(
            f"the {endpoint.name} endpoint cannot listen on {host}:{port}: the port {why} "
            f"(another Skydeck core or {endpoint.name} server?); choose another with "
            f"{endpoint.flag} PORT, or {endpoint.flag} 0 to turn it off"
        ) from None
    sock.setblocking(False)
    return sock


def _app(endpoint: _Endpoint, serve: Callable[[WebSocket], Awaitable[None]]) -> Starlette:
    async def greeting(request: Request) -> PlainTextResponse:
        return PlainTextResponse(endpoint.greeting, status_code=426 if "upgrade" in request.headers else 200)

    async def websocket(websocket: WebSocket) -> None:
        await serve(websocket)

    return Starlette(routes=[Route("/{path:path}", greeting), WebSocketRoute("/{path:path}", websocket)])


class _QuietServer(uvicorn.Server):
    """A uvicorn server inside the core's loop: the core handles signals, not this one."""

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        yield


class EndpointServers:
    """The endpoints' uvicorn servers, started and stopped with the core's app."""

    def __init__(self, settings: CoreSettings, sockets: dict[str, socket.socket]) -> None:
        self._settings = settings
        self._sockets = sockets
        self._running: list[tuple[uvicorn.Server, asyncio.Task[None]]] = []
        self.ports: dict[str, int] = {name: sock.getsockname()[1] for name, sock in sockets.items()}

    async def start(self, handlers: dict[str, Callable[[WebSocket], Awaitable[None]]]) -> None:
        """Serve each bound endpoint with its connection handler (by endpoint name)."""
        settings = self._settings
        for endpoint in ENDPOINTS:
            sock = self._sockets.get(endpoint.name)
            if sock is None:
                continue
            config = uvicorn.Config(
                _app(endpoint, handlers[endpoint.name]),
                lifespan="off",
                log_level="warning",
                access_log=False,
                # Frames up to 4x the message limit reach the adapter, which answers an oversized
                # one with the protocol's own error; beyond that the connection closes with 1009.
                ws_max_size=settings.max_message_bytes * 4,
                ws_ping_interval=settings.ping_interval_s,
                ws_ping_timeout=settings.ping_timeout_s,
                ws_per_message_deflate=False,
            )
            server = _QuietServer(config)
            task = asyncio.get_running_loop().create_task(server.serve(sockets=[sock]))
            self._running.append((server, task))
        for running, task in self._running:
            while not running.started and not task.done():
                await asyncio.sleep(0.005)

    async def stop(self) -> None:
        for server, _ in self._running:
            server.should_exit = True
            server.force_exit = True  # open connections are closed, not waited for
        for _, task in self._running:
            with contextlib.suppress(Exception):
                await task
        self._running.clear()
        for sock in self._sockets.values():
            sock.close()
