"""The optional access token (``SKYDECK_TOKEN``): who may call services and publish.

When a token is set, every service call and every publish needs it, as
``Authorization: Bearer TOKEN`` or, for browsers' WebSockets, ``?token=TOKEN``. Reading topics
and the registry stays open. Tokens are compared in constant time and never logged. (A node
checks its one token here; the core asks its fences, :mod:`services.access`, which also know
a class's tokens.)
"""

from __future__ import annotations

import hmac
import logging
import re

from starlette.requests import HTTPConnection

from services.runtime.wire import TOKEN_QUERY_PARAMETER

__all__ = [
    "NOT_AUTHORISED",
    "TOKEN_QUERY_PARAMETER",
    "WEBSOCKET_CLIENT_LOGGER",
    "RedactTokens",
    "bearer_token",
    "presented_token",
    "token_is_valid",
    "token_matches",
]

NOT_AUTHORISED = "publishing and service calls need the token: Authorization: Bearer TOKEN or ?token=TOKEN"


def bearer_token(authorization: str) -> str:
    """The token of an ``Authorization: Bearer TOKEN`` header's value, or ``""``."""
    scheme, _, value = authorization.partition(" ")
    return value.strip() if scheme.lower() == "bearer" and value else ""


def presented_token(connection: HTTPConnection) -> str:
    """The token a request or WebSocket presents (header first, then the query), or ``""``."""
    token = bearer_token(connection.headers.get("authorization", ""))
    if token:
        return token
    if not connection.scope.get("query_string"):
        return ""  # no query to parse (a few percent of a forwarded call's work in the core)
    return connection.query_params.get(TOKEN_QUERY_PARAMETER, "")


def token_matches(expected: str, connection: HTTPConnection) -> bool:
    """Whether ``connection`` may act; always true when no token is configured."""
    return token_is_valid(expected, presented_token(connection))


def token_is_valid(expected: str, presented: str) -> bool:
    """Whether ``presented`` is the token (in constant time); always true when none is configured."""
    if not expected:
        return True
    return hmac.compare_digest(presented.encode(), expected.encode())


_SECRETS = re.compile(r"(?i)(authorization:\s*(?:bearer\s+)?|[?&]token=)[^\s&]+")
_KEYS = re.compile(r'("key":\s*")[^"]*')  # a session's key in a logged frame (RegisteredFrame)


class RedactTokens(logging.Filter):
    """Replaces the values of ``Authorization`` headers, ``token=`` queries and a session's
    ``"key"`` with ``***``."""

    def filter(self, record: logging.LogRecord) -> bool:
        text = record.getMessage()
        redacted = _KEYS.sub(r"\1***", _SECRETS.sub(r"\1***", text))
        if redacted != text:
            record.msg, record.args = redacted, None
        return True


# The websockets library logs every handshake header at DEBUG, the Authorization header (and so
# the token) among them: the node's outgoing sockets (session, links) log through this logger.
WEBSOCKET_CLIENT_LOGGER = logging.getLogger("skydeck.websockets")
WEBSOCKET_CLIENT_LOGGER.addFilter(RedactTokens())
