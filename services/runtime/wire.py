"""Skydeck's wire constants, in one place: WebSocket close codes, stream options and limits.

Every socket (node, gateway, session, and the protocol adapters) and the dashboard use these
values; the core serves them at ``GET /api/config`` so the browser never spells them again.
"""

from __future__ import annotations

import enum
from typing import Any

__all__ = [
    "DEFAULT_QUEUE",
    "MAX_MESSAGE_BYTES",
    "MAX_QUEUE",
    "MAX_RATE_HZ",
    "STALL_CHECK_PERIOD_S",
    "TOKEN_QUERY_PARAMETER",
    "Close",
    "wire_description",
]


class Close(enum.IntEnum):
    """Why a Skydeck WebSocket was closed (RFC 6455 codes, then Skydeck's own 4000+)."""

    NORMAL = 1000
    UNSUPPORTED = 1003  # a binary frame where JSON text is expected, or a read-only stream
    INVALID_FRAME = 1007  # not valid JSON, or not of the topic's type (the reason names the field)
    POLICY = 1008  # a bad query option, an unknown type, a missing token, another site's page
    TOO_BIG = 1009  # a frame over MAX_MESSAGE_BYTES
    INTERNAL = 1011  # the server failed
    REPLACED = 4000  # a node session: a newer node took this name
    STALLED = 4001  # a reader took nothing for SKYDECK_STALL_TIMEOUT_S while frames waited


# -- limits -------------------------------------------------------------------------------------
# Frames and bodies above this are refused (close 1009, HTTP 413): a camera frame is ~20 KiB,
# so 1 MiB leaves room while bounding what one client can make a process buffer.
MAX_MESSAGE_BYTES = 1 << 20

# -- stream options (``ws://HOST/TOPIC?queue=N&rate=HZ&mode=...``) ------------------------------
DEFAULT_QUEUE = 100
"""Frames a reader may fall behind before its oldest are dropped (ROS's queue_size)."""
MAX_QUEUE = 10_000
MAX_RATE_HZ = 1_000.0

STALL_CHECK_PERIOD_S = 0.5
"""How often a reader is checked for a stall (``stall_timeout_s`` of the settings)."""

TOKEN_QUERY_PARAMETER = "token"
"""Browsers cannot set headers on a WebSocket: they send the token as ``?token=``."""


def wire_description() -> dict[str, Any]:
    """The constants a client needs, as served at ``GET /api/config``."""
    return {
        "close_codes": {code.name.lower(): int(code) for code in Close},
        "limits": {
            "max_message_bytes": MAX_MESSAGE_BYTES,
            "default_queue": DEFAULT_QUEUE,
            "max_queue": MAX_QUEUE,
            "max_rate_hz": MAX_RATE_HZ,
        },
        "token_query_parameter": TOKEN_QUERY_PARAMETER,
        "encodings": ["json", "msgpack"],
    }
