"""The gateway: every topic and service name answered by the core, routed to the node behind it.

- ``POST /NAME``: a service call, forwarded to the hosting node (404 unknown, 503 unreachable,
  504 timeout, each with a ``detail`` that says what to do).
- ``GET /NAME``: the latest message of a topic, from a publisher.
- ``ws://CORE/NAME``: the topic's stream (see :mod:`services.core.gateway_topic`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from fastapi.responses import JSONResponse, Response
from starlette.requests import Request
from starlette.types import ASGIApp, Receive, Scope, Send
from starlette.websockets import WebSocket

from services.core.core_node import CORE_NODE, CoreNode
from services.core.gateway_topic import GatewayTopic, declared_type
from services.core.registry import Registry
from services.core.settings import CoreSettings
from services.runtime.auth import NOT_AUTHORISED, presented_token, token_equals
from services.runtime.edge.topic_socket import serve_topic_socket
from services.runtime.http_client import HttpClient, HttpError, HttpTimeout
from shared_models import InvalidNameError, resolve_name
from shared_models.errors import SkydeckError

__all__ = ["Gateway", "GatewayError", "ServiceCallsFirst", "ServiceReply"]


class GatewayError(SkydeckError):
    """The core could not get an answer from a service; ``http_status`` says why."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status

    @property
    def http_status(self) -> int:  # type: ignore[override]
        return self.status


@dataclass(frozen=True, slots=True)
class ServiceReply:
    """A node's answer to a service call, as it sent it."""

    status: int
    body: bytes
    content_type: str | None


def _error(status_code: int, detail: str) -> JSONResponse:
    return JSONResponse({"detail": detail}, status_code=status_code)


class Gateway:
    """Routes names to nodes for HTTP and WebSocket clients of the core."""

    def __init__(self, registry: Registry, core: CoreNode, settings: CoreSettings, http: HttpClient) -> None:
        self._registry = registry
        self._core = core
        self._settings = settings
        self._http = http

    # -- HTTP ---------------------------------------------------------------------------------

    async def handle_http(self, request: Request) -> Response:
        """Route one GET (latest message) or POST (service call) by its path."""
        try:
            name = resolve_name(request.scope["path"])  # decoded: the name as the user wrote it
        except InvalidNameError as error:
            return _error(404, str(error))
        if request.method == "POST":
            return await self._call_service(name, request)
        return await self._latest(name)

    async def _call_service(self, name: str, request: Request) -> Response:
        try:
            reply = await self.call_service(
                name, await request.body(), token=presented_token(request), content_type=request.headers.get("content-type")
            )
        except SkydeckError as error:
            return _error(error.http_status, str(error))
        return Response(reply.body, status_code=reply.status, media_type=reply.content_type)

    async def call_service(
        self, name: str, body: bytes, *, token: str = "", content_type: str | None = "application/json"
    ) -> ServiceReply:
        """The one way the core calls a service: for HTTP clients and protocol adapters alike.

        Returns the node's answer whatever its status (a refusal is an answer); raises
        :class:`GatewayError` (404 unknown, 405 a topic, 401 no token, 503 unreachable,
        504 timeout), each with a message that says what to do.
        """
        found = self._registry.service(name)
        if found is None:
            if self._registry.topic_type(name) is not None:
                raise GatewayError(405, f"{name} is a topic, not a service: GET it or open a WebSocket to it")
            raise GatewayError(404, f"no service {name}: see `skydeck service list` or GET /api/graph")
        # Checked here as well as on the node: a call through the core is refused even when the
        # node behind it was started without the token.
        if not token_equals(self._settings.token, token):
            raise GatewayError(401, NOT_AUTHORISED)
        _, record = found
        node = record.description.name
        url = record.description.url.rstrip("/") + name
        headers = {"content-type": content_type} if content_type else {}
        if token:
            headers["authorization"] = f"Bearer {token}"  # also when it came as ?token= (a browser)
        try:
            reply = await self._http.post(url, body, headers=headers, timeout_s=self._settings.gateway_timeout_s)
        except ValueError:  # a ?token= with a line break: never put it into a header
            raise GatewayError(400, "the token holds characters a token cannot have") from None
        except HttpTimeout:
            raise GatewayError(
                504,
                f"{name} on node {node} did not answer within {self._settings.gateway_timeout_s:g} s: "
                f"is its handler stuck? see `skydeck node info {node}`",
            ) from None
        except HttpError:
            raise GatewayError(
                503, f"node {node} hosting {name} is not reachable at {url}: is it running? see `skydeck node list`"
            ) from None
        return ServiceReply(reply.status, reply.body, reply.headers.get("content-type"))

    async def _latest(self, name: str) -> Response:
        endpoint = self._core.endpoint(name)
        if endpoint is not None and endpoint.latest_frame is not None:
            return Response(endpoint.latest_frame, media_type="application/json")
        publishers = [p for p in self._registry.publishers(name) if p.node != CORE_NODE]
        for publisher in publishers:
            try:
                reply = await self._http.get(publisher.url.rstrip("/") + name, timeout_s=2.0)
            except HttpError:
                continue
            if reply.status == 200:
                return Response(reply.body, media_type="application/json")
        if publishers:
            return _error(404, f"no message on {name} yet")
        if self._registry.service(name) is not None:
            return _error(405, f"{name} is a service: call it with POST")
        if self._registry.topic_type(name) is not None:
            return _error(404, f"{name} has no publisher: see `skydeck topic info {name}`")
        return _error(404, f"no topic or service {name}: see `skydeck topic list` or GET /api/graph")

    # -- WebSocket ----------------------------------------------------------------------------

    async def handle_stream(self, websocket: WebSocket) -> None:
        """A topic's stream through the core node (see :mod:`services.core.gateway_topic`)."""
        await serve_topic_socket(
            websocket, self._find_topic, token=self._settings.token, stall_timeout_s=self._settings.reader_stall_s
        )

    def _find_topic(self, websocket: WebSocket) -> GatewayTopic:
        name = resolve_name(websocket.scope["path"])  # InvalidNameError closes with 1008
        declared = declared_type(websocket.query_params.get("type"))
        return GatewayTopic(self._core, self._registry, name, declared)


class ServiceCallsFirst:
    """A POST to a registered service's name goes straight to :meth:`Gateway.call_service`,
    before FastAPI tries every route of the core: the gateway's half of a forwarded call.

    Installed inside the body-size and same-origin checks, so those still apply.
    """

    def __init__(self, app: ASGIApp, registry: Registry, gateway: Callable[[], Gateway | None]) -> None:
        self.app = app
        self._registry = registry
        self._gateway = gateway

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        gateway = self._gateway()
        if (
            scope["type"] != "http"
            or scope["method"] != "POST"
            or gateway is None
            or self._registry.service(scope["path"]) is None
        ):
            await self.app(scope, receive, send)
            return
        request = Request(scope, receive)
        response = await gateway._call_service(scope["path"], request)
        await response(scope, receive, send)
