"""Refusing other web sites: a browser page from another origin may not call, publish or stream.

Without CORS headers a browser already hides cross-origin *responses*, but it still *sends* a
simple cross-origin POST (no preflight), and WebSockets have no CORS at all: any page the user
visits could take off the drone at ``127.0.0.1:8000`` or read its streams. Browsers always say
where a request comes from (``Origin``); the CLI, nodes and curl send none. So a POST or a
WebSocket handshake whose ``Origin`` is not this server's own address is refused: HTTP 403, or a
WebSocket closed before it opens (which browsers report as a failed connection).
"""

from __future__ import annotations

import json
from urllib.parse import urlsplit

from starlette.types import ASGIApp, Receive, Scope, Send

from services.runtime.wire import Close

__all__ = ["SameOriginOnly"]

_SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})


class SameOriginOnly:
    """Refuse POSTs and WebSockets from browser pages of other origins (403 / close 1008)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        guarded = scope["type"] == "websocket" or (scope["type"] == "http" and scope["method"] not in _SAFE_METHODS)
        if not guarded or _same_origin(scope):
            await self.app(scope, receive, send)
            return
        reason = "cross-origin request refused: open the dashboard from this server, or call it without a browser"
        if scope["type"] == "websocket":
            await receive()  # websocket.connect
            await send({"type": "websocket.close", "code": int(Close.POLICY), "reason": reason})
            return
        body = json.dumps({"detail": reason}).encode()
        await send({
            "type": "http.response.start",
            "status": 403,
            "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())],
        })
        await send({"type": "http.response.body", "body": body})


def _same_origin(scope: Scope) -> bool:
    origin = host = None
    for key, value in scope["headers"]:
        if key == b"origin":
            origin = value.decode("latin-1")
        elif key == b"host":
            host = value.decode("latin-1")
    if origin is None:
        return True  # not a browser page: the CLI, a node, curl
    return host is not None and urlsplit(origin).netloc.lower() == host.lower()
