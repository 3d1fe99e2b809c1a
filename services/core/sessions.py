"""The core's side of node sessions (``/api/session``): register, update, stats, leave."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time

from pydantic import ValidationError
from starlette.websockets import WebSocket, WebSocketDisconnect

from services.core.registry import Registry
from services.runtime.auth import token_matches
from services.runtime.edge.frames import close_with
from services.runtime.protocol import (
    CoreFrameModel,
    NodeDescription,
    RegisteredFrame,
    RegisterFrame,
    RejectedFrame,
    StatsFrame,
    UpdateFrame,
    node_frames,
)
from services.runtime.wire import Close
from shared_models.definitions.errors import DefinitionConflict, DefinitionError
from shared_models.definitions.loader import learn_definitions

__all__ = ["serve_session"]

logger = logging.getLogger("skydeck.core")

NOT_AUTHORISED_SESSION = "registering needs the core's token (SKYDECK_TOKEN): Authorization: Bearer TOKEN"
# A node with the wrong token retries twice a second: say so once in a while, not every time.
_REFUSAL_LOG_EVERY_S = 10.0
_last_refusal_log_s = -_REFUSAL_LOG_EVERY_S


async def serve_session(websocket: WebSocket, registry: Registry, *, token: str = "") -> None:
    """Hold one node's registration for as long as its socket is open.

    With a ``token``, a session that does not present it is closed with 1008 before it can
    register: otherwise any local process could take a node's name and redirect its callers.
    """
    await websocket.accept()
    if not token_matches(token, websocket):
        _log_refusal(websocket)
        await close_with(websocket, Close.POLICY, NOT_AUTHORISED_SESSION)
        return
    outgoing: asyncio.Queue[CoreFrameModel] = asyncio.Queue()
    writer = asyncio.create_task(_write(websocket, outgoing))
    name = None
    send = outgoing.put_nowait
    try:
        try:
            first = node_frames.validate_json(await websocket.receive_text())
        except (ValidationError, KeyError, RuntimeError) as error:
            await close_with(websocket, Close.INVALID_FRAME, f"expected a register frame: {error}")
            return
        if not isinstance(first, RegisterFrame):
            await close_with(websocket, Close.INVALID_FRAME, "the first frame must be a register frame")
            return
        if (refusal := _learn_types(first.node)) is not None:
            await _refuse(websocket, writer, refusal)
            return
        name = first.node.name
        outgoing.put_nowait(RegisteredFrame())
        replaced = registry.register(first.node, send)
        if replaced is not None:
            replaced.inbox(RejectedFrame(reason=f"a newer node took the name {name} (pid {first.node.pid})"))
        logger.info("node %s registered from %s (pid %d)", name, first.node.url, first.node.pid)
        while True:
            try:
                frame = node_frames.validate_json(await websocket.receive_text())
            except ValidationError as error:
                await close_with(websocket, Close.INVALID_FRAME, f"not a session frame: {error.errors()[0]['msg']}")
                return
            except KeyError:  # Starlette's receive_text() on a binary frame
                await close_with(websocket, Close.UNSUPPORTED, "session frames are JSON text, not binary")
                return
            if isinstance(frame, UpdateFrame) and frame.node.name == name:
                if (refusal := _learn_types(frame.node)) is not None:
                    await _refuse(websocket, writer, refusal)
                    return
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


def _learn_types(node: NodeDescription) -> str | None:
    """Learn the definitions of the node's own types (so every client of the core knows them);
    the reason to refuse the node when one cannot be read or differs from the known one."""
    if not node.interfaces:
        return None
    try:
        learned = learn_definitions(node.interfaces, source=f"node {node.name}")
    except (DefinitionError, DefinitionConflict) as error:
        logger.warning("refused node %s: %s", node.name, error)
        return str(error)
    if learned:
        logger.info("learned %s from node %s", ", ".join(learned), node.name)
    return None


async def _refuse(websocket: WebSocket, writer: asyncio.Task[None], reason: str) -> None:
    """Tell the node why it is refused (it stops, saying so), then close."""
    writer.cancel()
    with contextlib.suppress(asyncio.CancelledError):
        await writer
    with contextlib.suppress(WebSocketDisconnect, RuntimeError, OSError):
        await websocket.send_text(RejectedFrame(reason=reason).model_dump_json())
    await close_with(websocket, Close.POLICY, reason)


def _log_refusal(websocket: WebSocket) -> None:
    global _last_refusal_log_s
    now = time.monotonic()
    if now - _last_refusal_log_s >= _REFUSAL_LOG_EVERY_S:
        _last_refusal_log_s = now
        client = websocket.client
        where = f"{client.host}:{client.port}" if client else "an unknown peer"
        logger.warning("refused a node session from %s: no token or the wrong one (is its SKYDECK_TOKEN set?)", where)


async def _write(websocket: WebSocket, outgoing: asyncio.Queue[CoreFrameModel]) -> None:
    with contextlib.suppress(WebSocketDisconnect, RuntimeError, OSError):
        while True:
            frame = await outgoing.get()
            await websocket.send_text(frame.model_dump_json())
            # A rejection ends the session: the node's name now belongs to a newer node.
            if isinstance(frame, RejectedFrame):
                await close_with(websocket, Close.REPLACED, "replaced by a newer node with the same name")
                return
