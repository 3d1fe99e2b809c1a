"""Bad input for the tests that check refusals: bad JSON documents for a type, and how to read the
close code a WebSocket server answers a bad frame with.

An oversized frame is sent as its header alone (a masked client frame that declares more bytes
than the server's limit). The server refuses on the declared length, before reading a payload;
writing a real megabyte instead races the server's close: when the server closes with bytes of
ours still unread, its kernel resets the connection and the close frame (1009) can be lost.
"""

from __future__ import annotations

import json
import math
import os
import struct
from collections.abc import Iterator
from typing import Any

from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

__all__ = ["OversizedFrame", "bad_payloads", "close_of", "oversized_header"]

_TEXT, _BINARY = 0x1, 0x2


class OversizedFrame:
    """A frame that declares ``length`` payload bytes; ``close_of`` sends only its header."""

    def __init__(self, length: int, *, binary: bool = False) -> None:
        self.header = oversized_header(length, binary=binary)


def oversized_header(length: int, *, binary: bool = False) -> bytes:
    """A final, masked client frame header announcing ``length`` bytes (RFC 6455, section 5.2)."""
    opcode = _BINARY if binary else _TEXT
    return struct.pack("!BBQ", 0x80 | opcode, 0x80 | 127, length) + os.urandom(4)


def close_of(url: str, payload: str | bytes | OversizedFrame) -> tuple[int | None, str]:
    """Send one frame on a new socket to ``url``; the close code and reason the server answered."""
    with connect(url, max_size=None, open_timeout=5) as websocket:
        if isinstance(payload, OversizedFrame):
            websocket.socket.sendall(payload.header)
        else:
            websocket.send(payload)
        try:
            while True:  # a stream may deliver messages before it closes on our frame
                websocket.recv(timeout=5)
        except ConnectionClosed as closed:
            return (closed.rcvd.code, closed.rcvd.reason) if closed.rcvd else (None, "")
        except TimeoutError:
            return None, "still open"


def _leaves(value: Any, path: tuple[Any, ...] = ()) -> Iterator[tuple[tuple[Any, ...], Any]]:
    if isinstance(value, dict):
        for key, item in value.items():
            yield from _leaves(item, (*path, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from _leaves(item, (*path, index))
    else:
        yield path, value


def _replaced(value: Any, path: tuple[Any, ...], new: Any) -> Any:
    if not path:
        return new
    copy = json.loads(json.dumps(value))
    target = copy
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = new
    return copy


def _wrong(value: Any) -> Any:
    """A value of another type that pydantic's lax mode will not coerce."""
    return [1] if isinstance(value, str) else "fast"


def bad_payloads(default: dict[str, Any]) -> dict[str, bytes]:
    """Bad JSON documents for a type whose default value (as JSON) is ``default``."""
    text = json.dumps(default)
    cases = {
        "malformed": b"{not json",
        "truncated": text[: max(1, len(text) // 2)].encode(),
        "wrong top-level type": b"[1, 2]",
        "unknown field": json.dumps({**default, "bogus_field": 1}).encode(),
    }
    leaves = list(_leaves(default))
    if leaves:
        path, value = leaves[-1]
        cases["wrong field type"] = json.dumps(_replaced(default, path, _wrong(value))).encode()
    floats = [(path, value) for path, value in leaves if isinstance(value, float)]
    if floats:
        path, _ = floats[0]
        cases["NaN"] = json.dumps(_replaced(default, path, math.nan)).encode()
        cases["Infinity"] = json.dumps(_replaced(default, path, math.inf)).encode()
        # pydantic's lax mode would coerce these two: the JSON schema says number, so must we
        cases["number as a string"] = json.dumps(_replaced(default, path, "1.5")).encode()
        cases["boolean for a number"] = json.dumps(_replaced(default, path, True)).encode()
    return cases
