"""The ``skydeck core`` process: the core, with the endpoints of the table plugged in.

    serve(CoreProcessSettings(port=8000))              # what `skydeck core` runs
    app = create_core_app(settings)                    # the same app, for a harness to serve

This is the one registration point of the protocol endpoints: each row of
:data:`~services.protocols.endpoints.ENDPOINTS` is loaded as its package's plugin and handed to
the core's app factory with the socket of its own port, bound first (:func:`bind_endpoints`),
so a port in use is one clear error at start-up (:class:`EndpointPortBusy`), not a traceback.
"""

from __future__ import annotations

import errno
import socket

from fastapi import FastAPI

from services.core.app import create_app
from services.core.endpoint_servers import ServedEndpoint
from services.core.server import listen
from services.core.server import serve as serve_core
from services.protocols.endpoints import ENDPOINTS, Endpoint, load_plugin
from services.protocols.settings import CoreProcessSettings
from shared_models.errors import SkydeckError

__all__ = ["EndpointPortBusy", "bind_endpoints", "create_core_app", "serve", "served_endpoints"]


class EndpointPortBusy(SkydeckError):
    """A protocol endpoint's port is taken (or cannot be bound) at start-up."""


def serve(settings: CoreProcessSettings) -> None:
    """Serve the core and its endpoints until Ctrl-C or SIGTERM; the core's port, then each
    endpoint's, is bound first (NodeError, EndpointPortBusy: one line each)."""
    core_socket = listen(settings)
    try:
        sockets = bind_endpoints(settings)
    except BaseException:
        core_socket.close()
        raise
    serve_core(settings, core_socket=core_socket, endpoints=served_endpoints(sockets))


def create_core_app(settings: CoreProcessSettings, *, sockets: dict[str, socket.socket] | None = None) -> FastAPI:
    """The core's app with every endpoint plugged in, listening on ``sockets`` (by endpoint
    name) or, if not given, on sockets bound now from ``settings``."""
    return create_app(settings, endpoints=served_endpoints(bind_endpoints(settings) if sockets is None else sockets))


def served_endpoints(sockets: dict[str, socket.socket]) -> list[ServedEndpoint]:
    """Every endpoint of the table as a plugin, with its listening socket if it has one."""
    return [ServedEndpoint(load_plugin(endpoint), sockets.get(endpoint.name)) for endpoint in ENDPOINTS]


def bind_endpoints(settings: CoreProcessSettings) -> dict[str, socket.socket]:
    """Listening sockets of the endpoints whose port is on, by name; EndpointPortBusy names the
    first that cannot listen (those already bound are closed again)."""
    bound: dict[str, socket.socket] = {}
    try:
        for endpoint in ENDPOINTS:
            port = settings.endpoint_port(endpoint)
            if port:
                bound[endpoint.name] = _listen(settings.host, port, endpoint)
    except BaseException:
        for sock in bound.values():
            sock.close()
        raise
    return bound


def _listen(host: str, port: int, endpoint: Endpoint) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    # IPPROTO_TCP: asyncio sets TCP_NODELAY only on sockets that say they are TCP (as the core's).
    sock = socket.socket(family, socket.SOCK_STREAM, socket.IPPROTO_TCP)
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
