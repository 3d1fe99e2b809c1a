"""The gateway: every topic and service name answered by the core, routed to the node behind it.

- ``POST /NAME``: a service call, forwarded to the hosting node through the one service-call
  path (:mod:`services.core.service_calls`: 404 unknown, 401/403 fenced, 503 unreachable, 504
  timeout, each with a ``detail`` that says what to do).
- ``GET /NAME``: the latest message of a topic, from a publisher (401/403 if the caller may not
  read it).
- ``ws://CORE/NAME``: the topic's stream (see :mod:`services.core.gateway_topic`), fenced for
  the token the socket presents.

Each request or socket is admitted by the core's fences (:mod:`services.access`) once.
"""

from __future__ import annotations

from dataclasses import dataclass

from fastapi.responses import JSONResponse, Response
from starlette.requests import Request
from starlette.websockets import WebSocket

from services.access import Fences, Verb
from services.core.core_node import CORE_NODE, CoreNode
from services.core.gateway_topic import GatewayTopic, declared_type
from services.core.registry import Registry
from services.core.service_calls import ServiceCallFailed, ServiceCalls
from services.core.settings import CoreSettings
from services.runtime.auth import presented_token
from services.runtime.edge.topic_socket import serve_topic_socket
from services.runtime.http_client import HttpClient, HttpError
from shared_models import InvalidNameError, resolve_name

__all__ = ["Gateway"]


def _error(status_code: int, detail: str) -> JSONResponse:
    return JSONResponse({"detail": detail}, status_code=status_code)


@dataclass(frozen=True)
class Gateway:
    """Routes names to nodes for HTTP and WebSocket clients of the core."""

    registry: Registry
    core: CoreNode
    settings: CoreSettings
    http: HttpClient
    calls: ServiceCalls
    fences: Fences

    # -- HTTP ---------------------------------------------------------------------------------

    async def handle_http(self, request: Request) -> Response:
        """Route one GET (latest message) or POST (service call) by its path."""
        try:
            name = resolve_name(request.scope["path"])  # decoded: the name as the user wrote it
        except InvalidNameError as error:
            return _error(404, str(error))
        if request.method == "POST":
            return await self._call_service(name, request)
        refusal = self.fences.admit(presented_token(request)).refusal(Verb.READ, name)
        if refusal is not None:
            return _error(refusal.http_status, str(refusal))
        return await self._latest(name)

    async def _call_service(self, name: str, request: Request) -> Response:
        """An HTTP client's call that the core's own protocol did not take (a browser's, one with
        ``?token=``, any under another server): the same call, its failure as a JSON ``detail``."""
        caller = self.fences.admit(presented_token(request))
        try:
            reply = await self.calls.call(
                name, await request.body(), caller=caller, content_type=request.headers.get("content-type")
            )
        except ServiceCallFailed as failed:
            reply = failed.reply()
        return Response(reply.body, status_code=reply.status, media_type=reply.content_type)

    async def latest_frame(self, name: str) -> bytes | None:
        """The latest message of topic ``name`` (JSON), from the core or a publisher, if any."""
        endpoint = self.core.endpoint(name)
        if endpoint is not None and endpoint.latest_frame is not None:
            return endpoint.latest_frame.encode()
        for publisher in self.registry.publishers(name):
            if publisher.node == CORE_NODE:
                continue
            try:
                reply = await self.http.get(publisher.url.rstrip("/") + name, timeout_s=2.0)
            except HttpError:
                continue
            if reply.status == 200:
                return reply.body
        return None

    async def _latest(self, name: str) -> Response:
        frame = await self.latest_frame(name)
        if frame is not None:
            return Response(frame, media_type="application/json")
        if any(p.node != CORE_NODE for p in self.registry.publishers(name)):
            return _error(404, f"no message on {name} yet")
        if self.registry.service(name) is not None:
            return _error(405, f"{name} is a service: call it with POST")
        if self.registry.topic_type(name) is not None:
            return _error(404, f"{name} has no publisher: see `skydeck topic info {name}`")
        return _error(404, f"no topic or service {name}: see `skydeck topic list` or GET /api/graph")

    # -- WebSocket ----------------------------------------------------------------------------

    async def handle_stream(self, websocket: WebSocket) -> None:
        """A topic's stream through the core node (see :mod:`services.core.gateway_topic`): the
        topic fences the socket (reading when it opens, publishing at its first frame), so the
        edge checks no token of its own."""
        await serve_topic_socket(websocket, self._find_topic, token="", stall_timeout_s=self.settings.reader_stall_s)

    def _find_topic(self, websocket: WebSocket) -> GatewayTopic:
        name = resolve_name(websocket.scope["path"])  # InvalidNameError closes with 1008
        declared = declared_type(websocket.query_params.get("type"))
        return GatewayTopic(self.core, self.registry, name, declared, visitor=self.fences.admit(presented_token(websocket)))

