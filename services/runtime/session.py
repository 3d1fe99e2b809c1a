"""A node's live session with the core: register, stay registered, come back after a restart.

While the core is away the node keeps serving and its streams keep flowing; the session
retries every half second at most, so a restarted core sees every node again within a second.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from pydantic import ValidationError
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosed, InvalidHandshake, WebSocketException

from services.runtime.auth import WEBSOCKET_CLIENT_LOGGER
from services.runtime.edge.links import stream_url
from services.runtime.protocol import (
    NodeDescription,
    PublishersFrame,
    RegisteredFrame,
    RegisterFrame,
    RejectedFrame,
    StatsFrame,
    UpdateFrame,
    core_frames,
)
from services.runtime.wire import Close
from shared_models.errors import SkydeckError

if TYPE_CHECKING:
    from services.runtime.protocol import PublisherAddress

__all__ = ["CoreSession", "RegistrationRejected"]

_RETRY_FIRST_S = 0.1
_RETRY_MAX_S = 0.5
_STATS_PERIOD_S = 1.0

logger = logging.getLogger("skydeck.runtime")


class RegistrationRejected(SkydeckError):
    """The core refused this node (for example, a newer node took its name)."""


def _refusal(error: BaseException) -> str | None:
    """The core's reason when it closed the session as not allowed (1008), else None."""
    if isinstance(error, ConnectionClosed) and error.rcvd is not None and error.rcvd.code == Close.POLICY:
        return error.rcvd.reason
    return None


class CoreSession:
    """Keeps one node registered with the core at ``core_url``."""

    def __init__(
        self,
        core_url: str,
        *,
        describe: Callable[[], NodeDescription],
        stats: Callable[[], dict[str, int]],
        on_publishers: Callable[[str, list[PublisherAddress]], None],
        on_key: Callable[[str], None] | None = None,
        token: str = "",
        quiet_s: float = 0.0,
    ) -> None:
        self.core_url = core_url.rstrip("/")
        self._quiet_s = quiet_s  # a core starting beside this node: wait that long unsaid
        self._describe = describe
        self._stats = stats
        self._on_publishers = on_publishers
        self._on_key = on_key  # the key the core forwards admitted calls with (RegisteredFrame)
        self._headers = {"Authorization": f"Bearer {token}"} if token else None
        self._changed = asyncio.Event()
        self.registered = asyncio.Event()

    def mark_changed(self) -> None:
        """The node's entities changed: send an update (coalesced)."""
        self._changed.set()

    async def run(self) -> None:
        """Register and keep the session until cancelled; raises RegistrationRejected."""
        said_waiting = False
        registrations = 0
        retry_s = _RETRY_FIRST_S
        quiet_until = time.monotonic() + self._quiet_s
        url = stream_url(self.core_url, "/api/session")
        while True:
            try:
                async with connect(
                    url,
                    additional_headers=self._headers,
                    compression=None,
                    logger=WEBSOCKET_CLIENT_LOGGER,
                    open_timeout=2.0,
                    ping_interval=2.0,
                    ping_timeout=4.0,
                    close_timeout=1.0,
                    max_size=None,
                ) as websocket:
                    await self._register(websocket)
                    registrations += 1
                    name = self._describe().name
                    if registrations == 1:
                        logger.info("%s registered with core at %s", name, self.core_url)
                    else:
                        logger.info("%s registered again with core at %s", name, self.core_url)
                    said_waiting = False
                    retry_s = _RETRY_FIRST_S
                    self.registered.set()
                    await self._serve(websocket)
            except (OSError, TimeoutError, InvalidHandshake, WebSocketException, EOFError) as error:
                logger.debug("core session: %s", error)
                if (reason := _refusal(error)) is not None and not said_waiting:
                    logger.warning("the core at %s refused %s: %s; retrying", self.core_url, self._describe().name, reason)
                    said_waiting = True
            self.registered.clear()
            if not registrations and time.monotonic() < quiet_until:
                await asyncio.sleep(_RETRY_FIRST_S)  # the core is starting: ask again soon, unsaid
                continue
            if not said_waiting:
                if registrations:
                    logger.warning(
                        "lost core at %s; streams keep flowing, registering again when it is back", self.core_url
                    )
                else:
                    logger.warning("waiting for core at %s (start it with `skydeck core`)", self.core_url)
                said_waiting = True
            await asyncio.sleep(retry_s)
            retry_s = min(retry_s * 2, _RETRY_MAX_S)

    async def _register(self, websocket: ClientConnection) -> None:
        self._changed.clear()
        await websocket.send(RegisterFrame(node=self._describe()).model_dump_json())
        reply = self._parse(await websocket.recv())
        if isinstance(reply, RejectedFrame):
            raise RegistrationRejected(reply.reason)
        if isinstance(reply, RegisteredFrame) and self._on_key is not None:
            self._on_key(reply.key)
        if isinstance(reply, PublishersFrame):  # cannot happen before "registered"; be lenient
            self._on_publishers(reply.topic, reply.publishers)

    async def _serve(self, websocket: ClientConnection) -> None:
        sender = asyncio.create_task(self._send_updates(websocket))
        try:
            async for raw in websocket:
                frame = self._parse(raw)
                if isinstance(frame, PublishersFrame):
                    self._on_publishers(frame.topic, frame.publishers)
                elif isinstance(frame, RejectedFrame):
                    raise RegistrationRejected(frame.reason)
        finally:
            sender.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await sender

    async def _send_updates(self, websocket: ClientConnection) -> None:
        while True:
            with contextlib.suppress(TimeoutError):
                async with asyncio.timeout(_STATS_PERIOD_S):
                    await self._changed.wait()
            if self._changed.is_set():
                self._changed.clear()
                await websocket.send(UpdateFrame(node=self._describe()).model_dump_json())
            await websocket.send(StatsFrame(published=self._stats()).model_dump_json())

    @staticmethod
    def _parse(raw: str | bytes) -> RegisteredFrame | RejectedFrame | PublishersFrame:
        try:
            return core_frames.validate_json(raw)
        except ValidationError as error:
            raise WebSocketException(f"core sent a frame this node does not understand: {error}") from None
