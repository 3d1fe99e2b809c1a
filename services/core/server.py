"""Running the core under uvicorn; Ctrl-C and SIGTERM stop it with exit 0.

``skydeck core`` runs it through :mod:`services.protocols.core_process`, which plugs the
protocol endpoints in; this module knows none of them.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import signal
import socket
from collections.abc import Iterator, Sequence

import uvicorn
from starlette.types import ASGIApp

from services.core.app import create_app
from services.core.endpoint_servers import ServedEndpoint
from services.core.gateway_protocol import GatewayHttpProtocol
from services.core.settings import CoreSettings
from services.runtime.errors import NodeError
from services.runtime.executor import configure_logging, run
from services.runtime.server import bind

__all__ = ["core_config", "listen", "serve"]


class _Server(uvicorn.Server):
    """uvicorn without re-raising the stop signal after shutdown (a supervisor reads that as a crash)."""

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, self._stop)
        try:
            yield
        finally:
            for sig in (signal.SIGINT, signal.SIGTERM):
                loop.remove_signal_handler(sig)

    def _stop(self) -> None:
        if self.should_exit:
            self.force_exit = True  # a second Ctrl-C does not wait for open connections
        self.should_exit = True


def serve(
    settings: CoreSettings, *, core_socket: socket.socket | None = None, endpoints: Sequence[ServedEndpoint] = ()
) -> None:
    """Serve the core until Ctrl-C or SIGTERM, on ``core_socket`` if given (see :func:`listen`),
    with the protocol ``endpoints`` plugged in."""
    configure_logging(settings.log_level)
    sock = core_socket if core_socket is not None else listen(settings)
    app = create_app(settings, endpoints=endpoints)  # before announcing: a bad class file is its one line
    log = logging.getLogger("skydeck.core")
    log.info("core at http://%s:%d (dashboard /, every command /docs)", settings.host, settings.port)
    for served in endpoints:
        if served.socket is not None:
            log.info("%s endpoint at ws://%s:%d", served.plugin.name, settings.host, served.socket.getsockname()[1])
    config = core_config(app, settings)
    run(_Server(config).serve(sockets=[sock]))


def core_config(app: ASGIApp, settings: CoreSettings) -> uvicorn.Config:
    """uvicorn's settings for the core's app: its connections start on the gateway's protocol
    (:mod:`services.core.gateway_protocol`: service calls forwarded below ASGI)."""
    return uvicorn.Config(
        app,
        http=GatewayHttpProtocol,
        log_level="warning",
        access_log=False,
        ws_max_size=settings.max_message_bytes,
        ws_ping_interval=settings.ping_interval_s,
        ws_ping_timeout=settings.ping_timeout_s,
        ws_per_message_deflate=False,
    )


def listen(settings: CoreSettings) -> socket.socket:
    """The core's listening socket, bound before anything is announced: a port in use is one
    line naming it (uvicorn would log the core's address, then its own error, and exit 3)."""
    try:
        return bind(settings.host, settings.port)
    except NodeError as error:
        raise NodeError(f"the core {error}") from None
