"""A node's HTTP/WebSocket face: ``/health``, one stream + GET per topic, one POST per service.

Routes are added as the node creates entities, before or after it starts serving, so the node's
``/docs`` always shows what it offers. Errors become HTTP codes and close codes here, at the edge.
"""

from __future__ import annotations

import inspect
import logging
from collections.abc import Callable
from typing import Annotated, Any

from fastapi import Body, FastAPI
from fastapi.responses import JSONResponse, Response
from starlette.requests import Request as HTTPRequest
from starlette.websockets import WebSocket

from services.runtime.auth import NOT_AUTHORISED, presented_token, token_is_valid, token_matches
from services.runtime.edge.topic_socket import serve_topic_socket
from services.runtime.edge_checks import edge_checks
from services.runtime.endpoint import TopicEndpoint
from services.runtime.http_errors import install_error_handlers
from services.runtime.logger import NODE_LOGGERS
from services.runtime.service import Service
from shared_models import Message

__all__ = ["NodeApp"]


class NodeApp:
    """The FastAPI application of one participant (a node's, or the core's own)."""

    def __init__(
        self,
        name: str,
        *,
        token: str,
        max_message_bytes: int,
        stall_timeout_s: float,
        health: Callable[[], dict[str, Any]],
    ) -> None:
        self._token = token
        self._core_key = ""  # the core's key for calls it forwards (see accept_core_key)
        self._stall_timeout_s = stall_timeout_s
        self._logger = logging.getLogger(f"{NODE_LOGGERS}.{name.lstrip('/')}")
        self.fastapi = FastAPI(
            title=f"Skydeck node {name}",
            description="Topics (GET the latest, WebSocket for the stream) and services (POST) of this node.",
            version="0.1.0",
            redoc_url=None,
        )
        self.fastapi.add_middleware(edge_checks, max_bytes=max_message_bytes)
        install_error_handlers(self.fastapi)

        async def _health() -> dict[str, Any]:
            return health()

        self.fastapi.add_api_route("/health", _health, methods=["GET"], tags=["node"], summary="Liveness")

    def accept_core_key(self, key: str) -> None:
        """Take ``key`` as this node's token for service calls from now on, besides its own: the
        core it registered with forwards the calls its fences admitted with it (a new key each
        registration), so a caller the core lets through (an instructor calling a student's node)
        is not refused here for presenting another token than the node's."""
        self._core_key = key

    def _may_call(self, request: HTTPRequest) -> bool:
        if token_matches(self._token, request):
            return True
        return bool(self._core_key) and token_is_valid(self._core_key, presented_token(request))

    # -- topics -------------------------------------------------------------------------------

    def add_topic(self, endpoint: TopicEndpoint) -> None:
        """Serve ``endpoint`` at its name: GET for the latest message, WebSocket for the stream."""

        async def latest() -> Response:
            if endpoint.latest_frame is None:
                return JSONResponse(
                    {"detail": f"no message on {endpoint.name} yet: is its publisher running?"}, status_code=404
                )
            return Response(endpoint.latest_frame, media_type="application/json")

        async def stream(websocket: WebSocket) -> None:
            await serve_topic_socket(
                websocket, lambda _: endpoint, token=self._token, stall_timeout_s=self._stall_timeout_s
            )

        self.fastapi.add_api_route(
            endpoint.name,
            latest,
            methods=["GET"],
            tags=["topics"],
            summary=f"Latest {endpoint.type_name}",
            description=f"The latest message on topic {endpoint.name}; `ws://` the same path for the stream.",
            responses={200: {"model": endpoint.msg_type}, 404: {"description": "No message yet"}},
            name=f"topic:{endpoint.name}",
        )
        self.fastapi.add_api_websocket_route(endpoint.name, stream)
        self.fastapi.openapi_schema = None

    # -- services -----------------------------------------------------------------------------

    def add_service(self, service: Service) -> None:
        """Serve ``service`` as a POST at its name, typed by its Request and Response."""
        request_type: type[Message] = service.srv_type.Request
        response_type: type[Message] = service.srv_type.Response
        logger = self._logger

        async def call(http_request: Any, request: Any = None) -> Any:
            if not self._may_call(http_request):
                return JSONResponse({"detail": NOT_AUTHORISED}, status_code=401)
            # A ServiceHandlerError (the handler raised) answers 500 through install_error_handlers.
            return await service.handle(request if request is not None else request_type(), logger)

        # FastAPI reads types from the signature: give it this service's own request model, with
        # an empty body meaning the default request (`rosservice call /x` with no arguments).
        call.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
            [
                inspect.Parameter("http_request", inspect.Parameter.POSITIONAL_OR_KEYWORD, annotation=HTTPRequest),
                inspect.Parameter(
                    "request",
                    inspect.Parameter.POSITIONAL_OR_KEYWORD,
                    default=None,
                    annotation=Annotated[request_type | None, Body()],
                ),
            ]
        )
        self.fastapi.add_api_route(
            service.name,
            call,
            methods=["POST"],
            response_model=response_type,
            tags=["services"],
            summary=f"{service.name} ({service.srv_type.__ros_type__})",
            description=(service.srv_type.__doc__ or "").strip().splitlines()[0] if service.srv_type.__doc__ else "",
            name=f"service:{service.name}",
            responses={
                400: {"description": "The body is not readable as JSON text (not UTF-8)"},
                401: {"description": "Token required"},
                413: {"description": "The body is over the size limit"},
                500: {"description": "The handler failed"},
            },
        )
        self.fastapi.openapi_schema = None
