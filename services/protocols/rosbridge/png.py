"""rosbridge's ``png`` compression: a message's JSON text as the pixels of a PNG, in base64.

As rosbridge_suite makes it (and roslibjs's ``decompressPng`` reads it): the UTF-8 bytes are
the RGB pixels of a square-ish image (``width = floor(sqrt(n / 3))``, enough rows for the rest),
padded with newlines, which JSON reads as white space. The PNG is written here with zlib (one
IDAT chunk, no row filter); the op is ``{"op": "png", "data": BASE64}``, fragmented like any
other op when it is long.
"""

from __future__ import annotations

import base64
import json
import math
import struct
import zlib

__all__ = ["png_op", "png_text"]

_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_RGB = 2  # PNG colour type: truecolour, 3 samples a pixel


def png_op(text: str) -> str:
    """The ``png`` op carrying ``text`` (a whole rosbridge message as JSON)."""
    return json.dumps({"op": "png", "data": png_text(text)})


def png_text(text: str) -> str:
    """``text`` as the base64 of an RGB PNG whose pixels are its UTF-8 bytes."""
    data = text.encode()
    pixels = max(1, math.ceil(len(data) / 3))
    width = max(1, math.floor(math.sqrt(len(data) / 3)))
    height = math.ceil(pixels / width)
    data += b"\n" * (width * height * 3 - len(data))
    row = width * 3
    raw = b"".join(b"\x00" + data[start : start + row] for start in range(0, len(data), row))
    png = (
        _SIGNATURE
        + _chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, _RGB, 0, 0, 0))
        + _chunk(b"IDAT", zlib.compress(raw, 6))
        + _chunk(b"IEND", b"")
    )
    return base64.b64encode(png).decode("ascii")


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
