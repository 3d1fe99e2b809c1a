"""Serving an ASGI app on its own socket inside a running event loop (a node's uvicorn)."""

from __future__ import annotations

import asyncio
import contextlib
import socket
from collections.abc import Iterator

import uvicorn
from starlette.types import ASGIApp

from services.runtime.errors import NodeError
from services.runtime.settings import ProcessSettings

__all__ = ["AppServer", "bind"]

_SHUTDOWN_GRACE_S = 2.0


class _QuietServer(uvicorn.Server):
    """uvicorn without its own signal handling: the node owns Ctrl-C and SIGTERM."""

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        yield


class AppServer:
    """One app served by uvicorn on a socket bound at construction (so the port is known)."""

    def __init__(self, app: ASGIApp, settings: ProcessSettings, *, what: str) -> None:
        self._sock = bind(settings.host, settings.port)
        self.port: int = self._sock.getsockname()[1]
        self._what = what
        config = uvicorn.Config(
            app,
            log_level="warning",
            access_log=False,
            lifespan="off",
            ws_max_size=settings.max_message_bytes,
            ws_ping_interval=settings.ping_interval_s,
            ws_ping_timeout=settings.ping_timeout_s,
            ws_per_message_deflate=False,
        )
        self._server = _QuietServer(config)
        self._task: asyncio.Task[None] | None = None

    @property
    def address(self) -> str:
        """The address the socket is bound to (127.0.0.1 unless told otherwise)."""
        return str(self._sock.getsockname()[0])

    async def start(self) -> None:
        """Serve; returns once uvicorn accepts connections."""
        self._task = asyncio.get_running_loop().create_task(self._server.serve(sockets=[self._sock]))
        while not self._server.started:
            if self._task.done():
                await self._task
                raise NodeError(f"{self._what} could not start serving on port {self.port}")
            await asyncio.sleep(0.005)

    async def stop(self) -> None:
        """Stop serving: in-flight requests get a moment to finish; a hung handler does not hang us."""
        if self._task is None:
            return
        self._server.should_exit = True
        try:
            await asyncio.wait_for(asyncio.shield(self._task), _SHUTDOWN_GRACE_S)
        except TimeoutError:
            self._server.force_exit = True
            await self._task
        self._task = None


def bind(host: str, port: int) -> socket.socket:
    """A listening TCP socket on ``host:port``; NodeError with a hint if the port is taken."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    # IPPROTO_TCP, not 0: asyncio sets TCP_NODELAY only on sockets that say they are TCP, and
    # without it Nagle + delayed ACK hold every small HTTP reply for ~40 ms.
    sock = socket.socket(family, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
    except OSError as error:
        sock.close()
        raise NodeError(f"cannot listen on {host}:{port}: {error.strerror} (is another Skydeck process using it? pick --port)") from None
    sock.listen(128)
    sock.setblocking(False)
    return sock
