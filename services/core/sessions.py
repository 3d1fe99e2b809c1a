"""The core's side of node sessions (``/api/session``): register, update, stats, leave.

A session is admitted by the core's fences for the token it presents: a node registers only if
that token may run a node of its name and publish, read and serve what the node declares (a
student's node, only under their namespace, plus what the class shares); an update is checked
again. A refused node is told why in one line (it stops, saying so).
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import secrets
import time

from pydantic import ValidationError
from starlette.websockets import WebSocket, WebSocketDisconnect

from services.access import Fences, Pass, Role, Verb
from services.core.registry import Registry
from services.runtime.auth import presented_token
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
NOT_IN_CLASS_SESSION = "this core runs a class: registering a node needs your class token (SKYDECK_TOKEN=TOKEN)"
# A node with the wrong token retries twice a second: say so once in a while, not every time.
_REFUSAL_LOG_EVERY_S = 10.0
_last_refusal_log_s = -_REFUSAL_LOG_EVERY_S


async def serve_session(websocket: WebSocket, registry: Registry, fences: Fences) -> None:
    """Hold one node's registration for as long as its socket is open.

    Where a token is needed (a process token, a class), a session that presents none (or one
    nobody has) is closed with 1008 before it can register: otherwise any local process could
    take a node's name and redirect its callers. A node its token may not run is refused.
    """
    await websocket.accept()
    guest = fences.admit(presented_token(websocket))
    if guest.subject.role is Role.ANONYMOUS and not guest.unlimited:
        _log_refusal(websocket)
        await close_with(websocket, Close.POLICY, NOT_IN_CLASS_SESSION if fences.in_class else NOT_AUTHORISED_SESSION)
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
        if (refusal := _fenced(guest, first.node) or _learn_types(first.node)) is not None:
            await _refuse(websocket, writer, refusal)
            return
        name = first.node.name
        key = secrets.token_urlsafe(32)  # this session's: calls the core admitted reach the node with it
        outgoing.put_nowait(RegisteredFrame(key=key))
        replaced = registry.register(first.node, send, key=key)
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
                if (refusal := _fenced(guest, frame.node) or _learn_types(frame.node)) is not None:
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


def _fenced(guest: Pass, node: NodeDescription) -> str | None:
    """Why ``guest``'s token may not run ``node`` as it describes itself (its name, what it
    publishes, reads and serves), or None."""
    if guest.unlimited:
        return None
    asked = (
        [(Verb.REGISTER, node.name)]
        + [(Verb.PUBLISH, entity.name) for entity in node.publications]
        + [(Verb.READ, entity.name) for entity in node.subscriptions]
        + [(Verb.SERVE, entity.name) for entity in node.services]
    )
    for verb, name in asked:
        refusal = guest.refusal(verb, name)
        if refusal is not None:
            logger.warning("refused node %s (%s's token): %s", node.name, guest.subject, refusal)
            return str(refusal)
    return None


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
