"""The core's side of node sessions (``/api/session``): register, update, stats, leave."""

from __future__ import annotations

import asyncio
import contextlib
import logging

from pydantic import ValidationError
from starlette.websockets import WebSocket, WebSocketDisconnect

from services.core.registry import Registry
from services.runtime.protocol import (
    RegisteredFrame,
    RegisterFrame,
    RejectedFrame,
    StatsFrame,
    UpdateFrame,
    node_frames,
)
from services.runtime.stream import CLOSE_INVALID_FRAME, close_with

__all__ = ["serve_session"]

logger = logging.getLogger("skydeck.core")

# A private close code: this session's node name was taken by a newer node.
CLOSE_REPLACED = 4000


async def serve_session(websocket: WebSocket, registry: Registry) -> None:
    """Hold one node's registration for as long as its socket is open."""
    await websocket.accept()
    outgoing: asyncio.Queue[str] = asyncio.Queue()
    writer = asyncio.create_task(_write(websocket, outgoing))
    name = None
    send = outgoing.put_nowait
    try:
        try:
            first = node_frames.validate_json(await websocket.receive_text())
        except (ValidationError, KeyError, RuntimeError) as error:
            await close_with(websocket, CLOSE_INVALID_FRAME, f"expected a register frame: {error}")
            return
        if not isinstance(first, RegisterFrame):
            await close_with(websocket, CLOSE_INVALID_FRAME, "the first frame must be a register frame")
            return
        name = first.node.name
        outgoing.put_nowait(RegisteredFrame().model_dump_json())
        replaced = registry.register(first.node, send)
        if replaced is not None:
            replaced.send(RejectedFrame(reason=f"a newer node took the name {name} (pid {first.node.pid})").model_dump_json())
        logger.info("node %s registered from %s (pid %d)", name, first.node.url, first.node.pid)
        while True:
            try:
                frame = node_frames.validate_json(await websocket.receive_text())
            except ValidationError as error:
                await close_with(websocket, CLOSE_INVALID_FRAME, f"not a session frame: {error.errors()[0]['msg']}")
                return
            if isinstance(frame, UpdateFrame) and frame.node.name == name:
                registry.update(frame.node, send)
            elif isinstance(frame, StatsFrame):
                registry.record_stats(name, frame.published)
    except (WebSocketDisconnect, RuntimeError):
        pass
    finally:
        writer.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            await writer
        if name is not None:
            registry.unregister(name, send)
            logger.info("node %s left", name)


async def _write(websocket: WebSocket, outgoing: asyncio.Queue[str]) -> None:
    with contextlib.suppress(WebSocketDisconnect, RuntimeError, OSError):
        while True:
            frame = await outgoing.get()
            await websocket.send_text(frame)
            # A rejection ends the session: the node's name now belongs to a newer node.
            if frame.startswith('{"op":"rejected"'):
                await close_with(websocket, CLOSE_REPLACED, "replaced by a newer node with the same name")
                return
