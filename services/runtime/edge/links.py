"""A subscriber's connection to one remote publisher, kept up until it is no longer wanted.

The link reconnects by itself (short backoff) when the publisher goes away and comes back,
which is how node-to-node streams survive a publisher restart or a missing core. Nodes link
in msgpack (:mod:`.encoding`): cheaper to make and to read than JSON, byte arrays as bytes; and every
link asks for batches (:mod:`.batch`), so a frame may hold several messages.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable

from websockets.asyncio.client import connect
from websockets.exceptions import InvalidHandshake, InvalidURI, WebSocketException
from websockets.typing import Subprotocol

from services.runtime.auth import WEBSOCKET_CLIENT_LOGGER
from services.runtime.edge.encoding import Encoding

__all__ = ["PublisherLink", "stream_url"]

_BACKOFF_FIRST_S = 0.05
_BACKOFF_MAX_S = 1.0

logger = logging.getLogger("skydeck.runtime")


def stream_url(base_url: str, topic: str, **query: object) -> str:
    """The WebSocket URL of ``topic`` on the node at ``base_url`` (``http://h:p`` -> ``ws://``)."""
    scheme, _, rest = base_url.rstrip("/").partition("://")
    ws_scheme = "wss" if scheme == "https" else "ws"
    params = "&".join(f"{key}={value}" for key, value in query.items() if value is not None)
    return f"{ws_scheme}://{rest}{topic}" + (f"?{params}" if params else "")


class PublisherLink:
    """Reads one publisher's stream of ``topic`` and hands every frame to ``on_frame`` (which
    may be a batch of several messages, and says how many it held: ``received`` counts them
    since the link last connected).

    ``reader``: this node's name, sent to the publisher when the node is in a lockstep run
    (:mod:`services.runtime.lockstep`), so that both ends count the messages between them."""

    def __init__(
        self,
        publisher_url: str,
        topic: str,
        on_frame: Callable[[str | bytes], int],
        *,
        publisher: str = "",
        reader: str = "",
        queue_size: int,
        max_message_bytes: int,
        ping_interval_s: float,
        ping_timeout_s: float,
        token: str = "",
        encoding: Encoding = Encoding.MSGPACK,
    ) -> None:
        self.topic = topic
        self.publisher = publisher
        self.received = 0
        # Links take batches: a publisher's burst costs one frame (services.runtime.edge.batch).
        self.url = stream_url(publisher_url, topic, queue=queue_size, batch=1, reader=reader or None)
        self._subprotocols = [Subprotocol(encoding.subprotocol)]
        self._on_frame = on_frame
        self._max_message_bytes = max_message_bytes
        self._ping_interval_s = ping_interval_s
        self._ping_timeout_s = ping_timeout_s
        self._headers = {"Authorization": f"Bearer {token}"} if token else None
        self.connected = asyncio.Event()

    async def run(self) -> None:
        """Connect, read, and reconnect with backoff, until cancelled."""
        backoff_s = _BACKOFF_FIRST_S
        while True:
            try:
                async with connect(
                    self.url,
                    subprotocols=self._subprotocols,
                    additional_headers=self._headers,
                    compression=None,
                    logger=WEBSOCKET_CLIENT_LOGGER,
                    max_size=self._max_message_bytes,
                    open_timeout=2.0,
                    ping_interval=self._ping_interval_s,
                    ping_timeout=self._ping_timeout_s,
                    close_timeout=1.0,
                ) as websocket:
                    self.received = 0  # a new stream: the publisher counts afresh too
                    self.connected.set()
                    backoff_s = _BACKOFF_FIRST_S
                    on_frame = self._on_frame
                    async for frame in websocket:
                        self.received += on_frame(frame)
            except (OSError, TimeoutError, InvalidHandshake, WebSocketException) as error:
                if isinstance(error, InvalidURI):
                    logger.error("cannot subscribe to %s at %s: %s", self.topic, self.url, error)
                    return
                logger.debug("link to %s lost: %s", self.url, error)
            self.connected.clear()
            await asyncio.sleep(backoff_s)
            backoff_s = min(backoff_s * 2, _BACKOFF_MAX_S)
