"""The checks every request to a Skydeck server meets before anything else, in one place for
the core and every node: a POST or WebSocket from a browser page of another site is refused
(:class:`~services.runtime.origin.SameOriginOnly`, 403 / close 1008), then a body over the
size limit (:class:`~services.runtime.limits.BodySizeLimit`, 413). The core's HTTP protocol
(:mod:`services.core.gateway_protocol`) answers below ASGI only calls these checks would pass
(no ``Origin``, a declared length within the limit) and hands every other request to them."""

from __future__ import annotations

from starlette.types import ASGIApp

from services.runtime.limits import BodySizeLimit
from services.runtime.origin import SameOriginOnly

__all__ = ["edge_checks"]


def edge_checks(app: ASGIApp, max_bytes: int) -> ASGIApp:
    """``app`` behind the edge checks; also a middleware factory (``add_middleware(edge_checks, max_bytes=...)``)."""
    return SameOriginOnly(BodySizeLimit(app, max_bytes=max_bytes))
