"""Fixtures shared by the suite: real cores and nodes on free loopback ports, in-process."""

from __future__ import annotations

import asyncio
import contextlib
import os
import socket
import time
from collections.abc import AsyncIterator, Awaitable, Callable

import httpx
import pytest
import uvicorn

from services.core.server import core_config
from services.protocols.core_process import create_core_app
from services.protocols.settings import CoreProcessSettings
from services.runtime import Node, NodeSettings
from services.runtime.ports import free_port_block

# The suite never binds the protocol endpoints' well-known ports (rosbridge 9090, Foxglove 8765):
# other test runs, helpers and a user's own launch use them on this machine. Every harness passes
# free ports or 0 itself; these zeros also cover any core a subprocess starts.
os.environ["SKYDECK_ROSBRIDGE_PORT"] = "0"
os.environ["SKYDECK_FOXGLOVE_PORT"] = "0"


def free_port() -> int:
    """A TCP port free on loopback right now."""
    return free_port_block(1)


def listening_socket() -> socket.socket:
    """A TCP socket listening on a free loopback port (a protocol endpoint's, held from here)."""
    sock = held_socket()
    sock.listen(128)
    return sock


def held_socket(port: int = 0) -> socket.socket:
    """A TCP socket bound on loopback (a free port for 0), not listening yet: it refuses
    connections as no server would, but holds the port until a server listens on it. A port
    picked free and bound later can be taken meanwhile (a client's ephemeral port), and uvicorn
    then exits the whole test process."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind(("127.0.0.1", port))
    except OSError:
        sock.close()
        raise
    sock.setblocking(False)
    return sock


async def held_again(port: int, timeout_s: float = 5.0) -> socket.socket:
    """:func:`held_socket` on ``port`` once more (a restart), retrying while a connection of the
    server before still holds it; the loop runs on meanwhile."""
    async with asyncio.timeout(timeout_s):
        while True:
            try:
                return held_socket(port)
            except OSError:
                await asyncio.sleep(0.05)


async def serve_on(server: uvicorn.Server, sock: socket.socket) -> asyncio.Task[None]:
    """Serve ``server`` on the held socket ``sock`` (it listens from now); returns once it does."""
    server.capture_signals = contextlib.nullcontext  # type: ignore[method-assign]
    task = asyncio.create_task(server.serve(sockets=[sock]))
    await wait_until(lambda: server.started or task.done(), what="the server to start")
    if not server.started:
        await task
        raise AssertionError("the test server did not start")
    return task


async def wait_until(predicate: Callable[[], bool], timeout_s: float = 5.0, what: str = "condition") -> None:
    """Poll ``predicate`` (for state with no event to await) until true or fail after ``timeout_s``."""
    try:
        async with asyncio.timeout(timeout_s):
            while not predicate():
                await asyncio.sleep(0.01)
    except TimeoutError:
        raise AssertionError(f"timed out after {timeout_s} s waiting for {what}") from None


def registered_nodes(core_url: str, names: set[str], timeout_s: float) -> dict[str, str]:
    """Node name -> URL from the core's graph once every one of ``names`` is registered; fails
    after ``timeout_s`` naming the missing ones. For processes the harness started (a thread)."""
    deadline = time.monotonic() + timeout_s
    nodes: dict[str, str] = {}
    while True:
        with contextlib.suppress(httpx.HTTPError):
            nodes = {n["name"]: n["url"] for n in httpx.get(core_url + "/api/graph", timeout=5).json()["nodes"]}
        if names <= nodes.keys():
            return nodes
        if time.monotonic() > deadline:
            raise AssertionError(f"not registered after {timeout_s:g} s: {sorted(names - nodes.keys())}")
        time.sleep(0.05)


async def await_registered(core_url: str, names: set[str], timeout_s: float) -> dict[str, str]:
    """:func:`registered_nodes` from a coroutine (waits in a thread, the loop runs on)."""
    return await asyncio.to_thread(registered_nodes, core_url, names, timeout_s)


class CoreProcess:
    """A real core on uvicorn, served from the test's event loop; can be stopped and restarted.
    It is what ``skydeck core`` runs: the core with the protocol endpoints plugged in."""

    def __init__(
        self, port: int | None = None, *, endpoint_sockets: dict[str, socket.socket] | None = None, **settings: object
    ) -> None:
        # A new core holds a free port from here; a restart on a given port binds it in start().
        # So do its protocol endpoints when given as listening sockets (see listening_socket).
        self._socket: socket.socket | None = None
        self._endpoint_sockets = endpoint_sockets
        if port is None:
            self._socket = held_socket()
            port = self._socket.getsockname()[1]
        self.port: int = port
        settings = {"rosbridge_port": 0, "foxglove_port": 0, **settings}  # endpoints off unless asked for
        self.settings = CoreProcessSettings(host="127.0.0.1", port=self.port, **settings)  # type: ignore[arg-type]
        self.url = f"http://127.0.0.1:{self.port}"
        self.app = None
        self._server: uvicorn.Server | None = None
        self._task: asyncio.Task[None] | None = None

    async def start(self) -> None:
        self.app = create_core_app(self.settings, sockets=self._endpoint_sockets)
        self._endpoint_sockets = None  # the app's now; a restart binds the settings' ports
        self._server = uvicorn.Server(core_config(self.app, self.settings))
        sock = self._socket if self._socket is not None else await held_again(self.port)
        self._socket = None  # the server's now: it closes it when it stops
        self._task = await serve_on(self._server, sock)

    async def stop(self) -> None:
        if self._server is not None and self._task is not None:
            self._server.should_exit = True
            self._server.force_exit = True
            await self._task
            self._server = None

    @property
    def registry(self):  # type: ignore[no-untyped-def]
        return self.app.state.registry  # type: ignore[union-attr]


@pytest.fixture
async def core() -> AsyncIterator[CoreProcess]:
    process = CoreProcess()
    await process.start()
    yield process
    await process.stop()


@pytest.fixture
async def start_node(core: CoreProcess) -> AsyncIterator[Callable[[Callable[[NodeSettings], Node]], Awaitable[Node]]]:
    """Start nodes built by ``factory(settings)`` against ``core``; all are stopped afterwards."""
    started: list[Node] = []

    async def start(factory: Callable[[NodeSettings], Node], *, registered: bool = True) -> Node:
        settings = NodeSettings(core_url=core.url, port=0, ping_interval_s=1.0, ping_timeout_s=2.0, stall_timeout_s=1.0)
        node = factory(settings)
        await node.start()
        started.append(node)
        if registered:
            await wait_until(lambda: node.get_name() in core.registry.nodes, what=f"{node.get_name()} to register")
        return node

    yield start
    for node in reversed(started):
        await node.stop()
