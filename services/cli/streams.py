"""Reading a topic's stream through the core, for the CLI's topic verbs."""

from __future__ import annotations

from collections.abc import AsyncIterator

from websockets.asyncio.client import connect
from websockets.exceptions import InvalidHandshake, InvalidStatus

from services.cli.core_client import auth_headers, core_url, get_json, ws_url
from services.cli.errors import CliError
from shared_models.close_codes import Close

__all__ = ["frames", "packed_frames", "warn_if_unpublished"]


async def frames(name: str, *, rate: float | None = None, queue: int | None = None) -> AsyncIterator[str]:
    """Every frame of ``name`` (as JSON text) through the core; CliError if it cannot be read."""
    async for frame in _stream(name, rate=rate, queue=queue):
        yield frame if isinstance(frame, str) else frame.decode()


async def packed_frames(name: str, *, queue: int | None = None) -> AsyncIterator[bytes]:
    """Every frame of ``name`` as msgpack (``?encoding=msgpack``), for verbs that print no message:
    cheaper for the core to send and for the CLI to read than JSON (an image is not base64)."""
    async for frame in _stream(name, queue=queue, encoding="msgpack"):
        yield frame if isinstance(frame, bytes) else frame.encode()


async def _stream(name: str, **query: object) -> AsyncIterator[str | bytes]:
    url = ws_url(name, **query)
    try:
        async with connect(url, additional_headers=auth_headers(), compression=None, max_size=None) as websocket:
            async for frame in websocket:
                yield frame
            if websocket.close_code not in (Close.NORMAL, Close.GOING_AWAY, None):
                raise CliError(f"{name}: the core closed the stream ({websocket.close_code}): {websocket.close_reason}")
    except (OSError, InvalidHandshake, TimeoutError) as error:
        if isinstance(error, InvalidStatus):
            raise CliError(f"the core refused the stream of {name}: HTTP {error.response.status_code}") from None
        raise CliError(
            f"cannot reach the core at {core_url()}: is it running? start it with `skydeck core` (or `make up`)"
        ) from None


def warn_if_unpublished(name: str) -> None:
    """rostopic's warning when nobody publishes ``name`` yet (the stream starts when one does)."""
    topics = {t["name"]: t for t in get_json("/api/graph")["topics"]}
    if name not in topics or not topics[name]["publishers"]:
        print(f"WARNING: topic [{name}] does not appear to be published yet", flush=True)
