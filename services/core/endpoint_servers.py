"""Protocol endpoints plugged into the core from above, and the small servers on their own ports.

The core knows no protocol. A protocol package (``services.protocols.rosbridge``, ...) gives an
:class:`EndpointPlugin`; the process that starts the core (``skydeck core``:
:mod:`services.protocols.core_process`) hands the core its plugins, each with the listening
socket of its own port if it has one (:class:`ServedEndpoint`). When the core starts, each plugin
is started on the core's parts (:class:`~services.core.access.CoreAccess`) and its connections
are served:

- on its own port, by a small ASGI app (one WebSocket route, and a line of text for a browser
  that opens the port) under a uvicorn server in the core's event loop, so every connection uses
  the same core node, registry and call path as the core's own routes;
- at ``core_path`` on the core's own port, if the plugin names one (rosbridge's ``/rosbridge``).

Unlike the core's own port, the endpoints' ports accept pages of any origin: Foxglove's web app
and roslibjs pages are served from elsewhere, as with rosbridge_server and foxglove_bridge. The
write token (``SKYDECK_TOKEN``) guards publishing and calls there as everywhere.
"""

from __future__ import annotations

import asyncio
import contextlib
import socket
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Protocol

import uvicorn
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import PlainTextResponse
from starlette.routing import Route, WebSocketRoute
from starlette.websockets import WebSocket

from services.core.access import CoreAccess
from services.core.settings import CoreSettings

__all__ = ["EndpointConnections", "EndpointPlugin", "EndpointServers", "ServedEndpoint"]


class EndpointConnections(Protocol):
    """A started endpoint: it serves each connection, and is closed when the core stops."""

    async def serve(self, websocket: WebSocket) -> None: ...

    def close(self) -> None: ...


@dataclass(frozen=True)
class EndpointPlugin:
    """A protocol the core serves, as its package declares it."""

    name: str  # "rosbridge": its row in the table of endpoints (services.protocols.endpoints)
    start: Callable[[CoreAccess], EndpointConnections]  # called once, when the core starts
    greeting: str  # what a browser opening the endpoint's own port over HTTP reads
    core_path: str | None = None  # also served at this path on the core's own port


@dataclass(frozen=True)
class ServedEndpoint:
    """A plugin, and the listening socket of its own port (None: not on a port of its own)."""

    plugin: EndpointPlugin
    socket: socket.socket | None = None


class _QuietServer(uvicorn.Server):
    """A uvicorn server inside the core's loop: the core handles signals, not this one."""

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        yield


class EndpointServers:
    """The started endpoints and their uvicorn servers, from the core's start to its stop."""

    def __init__(self, settings: CoreSettings, endpoints: Sequence[ServedEndpoint]) -> None:
        self._settings = settings
        self._endpoints = tuple(endpoints)
        self._started: dict[str, EndpointConnections] = {}
        self._running: list[tuple[uvicorn.Server, asyncio.Task[None]]] = []
        self.ports: dict[str, int] = {
            served.plugin.name: served.socket.getsockname()[1] for served in endpoints if served.socket is not None
        }

    def connections(self, name: str) -> EndpointConnections:
        """The started endpoint ``name`` (KeyError before the core started or for another name)."""
        return self._started[name]

    async def start(self, access: CoreAccess) -> None:
        """Start every plugin on the core's parts, and serve each on its own port if it has one."""
        for served in self._endpoints:
            self._started[served.plugin.name] = served.plugin.start(access)
        for served in self._endpoints:
            if served.socket is not None:
                self._serve(served.plugin, served.socket)
        for running, task in self._running:
            while not running.started and not task.done():
                await asyncio.sleep(0.005)

    def _serve(self, plugin: EndpointPlugin, sock: socket.socket) -> None:
        settings = self._settings
        config = uvicorn.Config(
            _app(plugin, self._started[plugin.name]),
            lifespan="off",
            log_level="warning",
            access_log=False,
            # Frames up to 4x the message limit reach the endpoint, which answers an oversized
            # one with the protocol's own error; beyond that the connection closes with 1009.
            ws_max_size=settings.max_message_bytes * 4,
            ws_ping_interval=settings.ping_interval_s,
            ws_ping_timeout=settings.ping_timeout_s,
            ws_per_message_deflate=False,
        )
        server = _QuietServer(config)
        task = asyncio.get_running_loop().create_task(server.serve(sockets=[sock]))
        self._running.append((server, task))

    async def stop(self) -> None:
        for server, _ in self._running:
            server.should_exit = True
            server.force_exit = True  # open connections are closed, not waited for
        for _, task in self._running:
            with contextlib.suppress(Exception):
                await task
        self._running.clear()
        for served in self._endpoints:
            if served.socket is not None:
                served.socket.close()
        for started in self._started.values():
            started.close()
        self._started.clear()


def _app(plugin: EndpointPlugin, connections: EndpointConnections) -> Starlette:
    async def greeting(request: Request) -> PlainTextResponse:
        return PlainTextResponse(plugin.greeting, status_code=426 if "upgrade" in request.headers else 200)

    async def websocket(websocket: WebSocket) -> None:
        await connections.serve(websocket)

    return Starlette(routes=[Route("/{path:path}", greeting), WebSocketRoute("/{path:path}", websocket)])
