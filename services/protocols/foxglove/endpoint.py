"""The Foxglove WebSocket protocol: Foxglove and Lichtblick on the core's one topic edge.

    ws://CORE:8765/   (``--foxglove-port``; 0 turns it off)
    subprotocols foxglove.websocket.v1 and foxglove.sdk.v1

On connect a client gets ``serverInfo`` and an ``advertise`` of every topic whose type the core
knows (JSON encoding, JSON schema, ROS type names: see :mod:`.payloads`), and of every service;
both follow the graph as it changes (:mod:`.graph`). Subscribing reads the topic through the
connection's :class:`~services.protocols.session.ClientSession`; messages arrive as binary
``0x01`` frames whose payload is made once for every connection. Clients publish (advertise,
then ``0x01`` client frames), call services (``0x02`` -> ``0x03`` or ``serviceCallFailure``),
get, set and follow parameters (:mod:`.parameter_ops`, named ``/node.param``), and follow the
connection graph. While a simulator publishes ``/clock``, the server offers ``time``: ``0x02``
time frames from ``/clock``, and message timestamps on the same clock. One connection's doings
are :mod:`.connection`'s.

A bad request is answered with a ``status`` (level 2, error) for that request only. A client
that stops reading is closed with 4001 (see :mod:`services.protocols.session`).
"""

from __future__ import annotations

import asyncio
import time

from starlette.websockets import WebSocket

from services.core.access import CoreAccess
from services.protocols.foxglove.connection import Connection, Shared
from services.protocols.foxglove.graph import GraphView
from services.protocols.foxglove.ops import SUBPROTOCOLS
from services.protocols.foxglove.payloads import Payloads
from services.protocols.session import ClientSession
from services.runtime.edge.frames import close_with
from services.runtime.wire import Close

__all__ = ["FoxgloveEndpoint"]


class FoxgloveEndpoint:
    """Serves Foxglove connections; payloads and channel ids are shared by all of them."""

    def __init__(self, access: CoreAccess) -> None:
        self.access = access
        self._shared = Shared(access, Payloads(), GraphView(access.registry), str(time.time_ns()))
        self._connections: set[Connection] = set()
        self._refresh_pending = False
        self._unwatch = access.registry.watch(self._graph_changed)

    async def serve(self, websocket: WebSocket) -> None:
        """One Foxglove connection, from handshake to close."""
        offered = websocket.scope.get("subprotocols", [])
        chosen = next((p for p in offered if p in SUBPROTOCOLS), None)
        if chosen is None:
            await websocket.accept()
            await close_with(
                websocket, Close.POLICY, "this is a Foxglove WebSocket endpoint: offer the subprotocol foxglove.websocket.v1"
            )
            return
        await websocket.accept(subprotocol=chosen)
        session = ClientSession.open(self.access, websocket, "foxglove")
        connection = Connection(self._shared, session)
        self._connections.add(connection)
        try:
            stalled = await session.serve(connection.run(websocket), advice="subscribe to fewer channels")
        finally:
            self._connections.discard(connection)
            connection.close()
        if stalled is not None:
            await close_with(websocket, stalled.code, stalled.reason)

    def close(self) -> None:
        self._unwatch()

    def _graph_changed(self) -> None:
        # Many registry changes come at once (a launch, a client subscribing): refresh once.
        if self._refresh_pending or not self._connections:
            return
        self._refresh_pending = True
        asyncio.get_running_loop().call_soon(self._refresh)

    def _refresh(self) -> None:
        self._refresh_pending = False
        self._shared.graph.update()
        for connection in list(self._connections):
            connection.spawn(connection.follow_graph())
