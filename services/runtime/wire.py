"""Skydeck's wire constants, in one place: WebSocket close codes, stream options and limits.

Every socket (node, gateway, session, and the protocol adapters) and the dashboard use these
values; the core serves them at ``GET /api/config`` so the browser never spells them again.
"""

from __future__ import annotations

from typing import Any

from shared_models.close_codes import Close

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
