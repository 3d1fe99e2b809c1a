"""Reading a topic's stream through the core, for the CLI's topic verbs."""

from __future__ import annotations

from collections.abc import AsyncIterator
from typing import Literal, overload

from websockets.asyncio.client import connect
from websockets.exceptions import InvalidHandshake, InvalidStatus

from services.cli.core_client import auth_headers, core_url, get_json, ws_url
from services.cli.errors import CliError
from services.cli.suggestions import did_you_mean, unknown
from shared_models.close_codes import Close

__all__ = ["check_topic", "frames"]


@overload
def frames(
    name: str, *, rate: float | None = None, queue: int | None = None, packed: Literal[False] = False
) -> AsyncIterator[str]: ...
@overload
def frames(name: str, *, rate: float | None = None, queue: int | None = None, packed: Literal[True]) -> AsyncIterator[bytes]: ...


async def frames(
    name: str, *, rate: float | None = None, queue: int | None = None, packed: bool = False
) -> AsyncIterator[str | bytes]:
    """Every frame of ``name`` through the core, as JSON text, or as msgpack with ``packed``
    (``?encoding=msgpack``: for verbs that print no message, cheaper for the core to send and
    for the CLI to read, an image's bytes not base64); CliError if it cannot be read.

    One generator, not one wrapping another: an async generator left inside another when the
    reader stops early is closed by the event loop's finaliser, which then fails loudly.
    """
    url = ws_url(name, rate=rate, queue=queue, encoding="msgpack" if packed else None)
    try:
        async with connect(url, additional_headers=auth_headers(), compression=None, max_size=None) as websocket:
            async for frame in websocket:
                if packed:
                    yield frame if isinstance(frame, bytes) else frame.encode()
                else:
                    yield frame if isinstance(frame, str) else frame.decode()
            if websocket.close_code not in (Close.NORMAL, Close.GOING_AWAY, None):
                raise CliError(f"{name}: the core closed the stream ({websocket.close_code}): {websocket.close_reason}")
    except (OSError, InvalidHandshake, TimeoutError) as error:
        if isinstance(error, InvalidStatus):
            raise CliError(f"the core refused the stream of {name}: HTTP {error.response.status_code}") from None
        raise CliError(
            f"cannot reach the core at {core_url()}: is it running? start it with `skydeck core` (or `make up`)"
        ) from None


def check_topic(name: str, *, wait: bool = True) -> None:
    """Before reading ``name``: rostopic's warning when nobody publishes it yet (the stream
    starts when one does), with the nearest names when the system has no such topic at all.
    With ``wait=False`` (a bounded read: ``echo --once``), a name the system lacks is an error."""
    topics = {t["name"]: t for t in get_json("/api/graph")["topics"]}
    if name in topics and topics[name]["publishers"]:
        return
    if name in topics:  # subscribed to, or published before: a name of this system
        print(f"WARNING: topic [{name}] does not appear to be published yet", flush=True)
        return
    if not wait:
        raise CliError(unknown("topic", name, topics, listing="skydeck topic list") + ", or wait for it with --timeout S")
    print(f"WARNING: topic [{name}] does not appear to be published yet{did_you_mean(name, topics)}", flush=True)
