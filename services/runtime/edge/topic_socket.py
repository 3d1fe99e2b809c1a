"""The one topic edge: every WebSocket on a topic, on a node or on the core, goes through here.

    await serve_topic_socket(websocket, find_port, token=settings.token)

It negotiates the encoding (JSON text, or msgpack: :mod:`.encoding`), accepts the socket, finds
the topic (``find_port``: a node's own endpoint, or the core's gateway view of the topic), reads
the options (``queue``, ``rate``, ``mode``, ``batch``), checks the token before a client may publish, and
pumps frames both ways. What a frame *means* is the port's:

- ``open(connection)``: a socket arrives; returns the latched frame to send it first, if any,
  in the connection's encoding (or raises a SkydeckError to refuse it: closed with its code);
- ``receive_frame(connection, frame)``: a client published a frame (text, or bytes on a msgpack
  socket): validate it and publish it,
  never back to the connection it came from (no echo); raise FrameRejected to refuse it;
- ``close(connection)``: the socket is gone.

Protocol adapters (rosbridge, Foxglove) use the same three calls on the same ports, so a frame
enters and leaves a topic in one place whatever the protocol. Problems close only the socket
they came from, with the close codes of :mod:`services.runtime.wire`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from starlette.websockets import WebSocket

from services.runtime.auth import NOT_AUTHORISED, token_matches
from services.runtime.edge.encoding import Encoding, negotiate
from services.runtime.edge.frames import FrameRejected, close_with
from services.runtime.edge.options import Mode, StreamOptions
from services.runtime.edge.outbox import Frame, Outbox
from services.runtime.edge.pump import serve_stream
from services.runtime.wire import Close
from shared_models.errors import SkydeckError

__all__ = ["TopicConnection", "TopicPort", "serve_topic_socket"]


@dataclass(eq=False)
class TopicConnection:
    """One client on one topic: where its frames go (``outbox``) and what it may do."""

    options: StreamOptions
    outbox: Outbox | None  # None: a publish-only client, sent nothing
    may_publish: bool
    encoding: Encoding = Encoding.JSON
    published: bool = False  # set by the port once a frame of this client was published


class TopicPort(Protocol):
    """One topic as sockets see it (see the module docstring)."""

    name: str

    def open(self, connection: TopicConnection) -> Frame | None: ...

    def receive_frame(self, connection: TopicConnection, frame: Frame) -> None: ...

    def close(self, connection: TopicConnection) -> None: ...


async def serve_topic_socket(
    websocket: WebSocket, find_port: Callable[[WebSocket], TopicPort], *, token: str, stall_timeout_s: float
) -> None:
    """Serve one topic socket from handshake to close (see the module docstring).

    ``find_port`` may raise any SkydeckError (an invalid name, an unknown ``?type=``): the
    socket is closed with that error's close code and message.
    """
    try:
        encoding, subprotocol = negotiate(websocket.query_params, websocket.scope.get("subprotocols", ()))
    except FrameRejected as refused:
        await websocket.accept()
        await close_with(websocket, refused.code, refused.reason)
        return
    await websocket.accept(subprotocol=subprotocol)
    try:
        options = StreamOptions.from_query(websocket.query_params)
        port = find_port(websocket)
        connection = TopicConnection(
            options=options,
            outbox=Outbox(options.outbox_size, encoding, batch=options.batch) if options.reads else None,
            may_publish=token_matches(token, websocket),
            encoding=encoding,
        )
        initial_frame = port.open(connection)  # a port may refuse the connection (the core's fences)
    except SkydeckError as error:
        await close_with(websocket, error.close_code, str(error))
        return

    def on_frame(frame: Frame) -> None:
        if not connection.may_publish:
            raise FrameRejected(Close.POLICY, NOT_AUTHORISED)
        port.receive_frame(connection, frame)

    try:
        rejected = await serve_stream(
            websocket,
            connection.outbox,
            options=options,
            encoding=encoding,
            initial_frame=initial_frame,
            on_frame=None if options.mode is Mode.SUBSCRIBE else on_frame,
            stall_timeout_s=stall_timeout_s,
        )
    finally:
        port.close(connection)
    if rejected is not None:
        # A stalled reader's close frame goes out behind the frames it has not read yet, when it
        # reads again; one that never does is ended by the server's keepalive (ping_timeout_s).
        await close_with(websocket, rejected.code, rejected.reason)
