"""The optional access token (``SKYDECK_TOKEN``): who may call services and publish.

When a token is set, every service call and every publish needs it, as
``Authorization: Bearer TOKEN`` or, for browsers' WebSockets, ``?token=TOKEN``. Reading topics
and the registry stays open. Tokens are compared in constant time and never logged.
"""

from __future__ import annotations

import hmac

from starlette.requests import HTTPConnection

__all__ = ["NOT_AUTHORISED", "TOKEN_QUERY_PARAMETER", "presented_token", "token_matches"]

TOKEN_QUERY_PARAMETER = "token"
NOT_AUTHORISED = "publishing and service calls need the token: Authorization: Bearer TOKEN or ?token=TOKEN"


def presented_token(connection: HTTPConnection) -> str:
    """The token a request or WebSocket presents (header first, then the query), or ``""``."""
    header = connection.headers.get("authorization", "")
    scheme, _, value = header.partition(" ")
    if scheme.lower() == "bearer" and value:
        return value.strip()
    return connection.query_params.get(TOKEN_QUERY_PARAMETER, "")


def token_matches(expected: str, connection: HTTPConnection) -> bool:
    """Whether ``connection`` may act; always true when no token is configured."""
    if not expected:
        return True
    return hmac.compare_digest(presented_token(connection).encode(), expected.encode())
