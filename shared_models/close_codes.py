"""WebSocket close codes: why a Skydeck socket was closed (RFC 6455 codes, then Skydeck's own).

In the lowest package so that the error tree (each error's ``close_code``), every socket and the
CLI name the same values; ``services.runtime.wire`` serves them to the dashboard.
"""

from __future__ import annotations

import enum

__all__ = ["Close"]


class Close(enum.IntEnum):
    """Why a Skydeck WebSocket was closed (RFC 6455 codes, then Skydeck's own 4000+)."""

    NORMAL = 1000
    GOING_AWAY = 1001  # the server is stopping, or the browser left the page
    UNSUPPORTED = 1003  # a binary frame where JSON text is expected, or a read-only stream
    INVALID_FRAME = 1007  # not valid JSON, or not of the topic's type (the reason names the field)
    POLICY = 1008  # a bad query option, an unknown type, a missing token, another site's page
    TOO_BIG = 1009  # a frame over MAX_MESSAGE_BYTES
    INTERNAL = 1011  # the server failed
    REPLACED = 4000  # a node session: a newer node took this name
    STALLED = 4001  # a reader took nothing for SKYDECK_STALL_TIMEOUT_S while frames waited
    RATE_LIMITED = 4002  # a student's token sent more than its rate through the core (SKYDECK_STUDENT_*)
