"""The core's application: registry, gateway, dashboard and one OpenAPI page for the system.

    app = create_app(CoreSettings(port=8000))

Routes, most specific first: ``/api/...`` (registry), ``/docs`` and ``/openapi.json``,
``/static/...`` and ``/`` (dashboard), ``/health``; every other path is a topic or service name
answered by the gateway.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import AsyncIterator, Awaitable, Callable, Sequence
from pathlib import Path
from typing import Any

from fastapi import FastAPI, Request, WebSocket
from fastapi.openapi.docs import get_swagger_ui_html
from fastapi.responses import FileResponse, HTMLResponse, JSONResponse, RedirectResponse, Response
from fastapi.staticfiles import StaticFiles
from starlette.routing import Route, WebSocketRoute
from starlette.types import Receive, Scope, Send

from services.access import Verb
from services.core.access import CoreAccess
from services.core.api import router as api_router
from services.core.classroom import router as class_router
from services.core.core_node import CORE_NODE, CORE_NODE_PATH, CoreNode
from services.core.endpoint_servers import EndpointServers, ServedEndpoint
from services.core.gateway import Gateway
from services.core.guests import Guests
from services.core.openapi import aggregate_openapi
from services.core.parameter_server import ParameterTree
from services.core.parameter_server import router as parameter_server_router
from services.core.recordings import Recordings
from services.core.recordings import router as recordings_router
from services.core.registry import Registry
from services.core.rosout_log import RosoutLog
from services.core.rosout_log import router as rosout_router
from services.core.service_calls import ServiceCalls
from services.core.sessions import serve_session
from services.core.settings import CoreSettings
from services.core.visitors import FencedEndpoint, core_fences, visitor
from services.core.visitors import router as access_router
from services.runtime.auth import presented_token
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.topic_socket import TopicPort, serve_topic_socket
from services.runtime.edge_checks import edge_checks
from services.runtime.http_client import HttpClient
from services.runtime.http_errors import install_error_handlers
from services.runtime.settings import reachable_host
from services.runtime.wire import Close

__all__ = ["CoreApp", "create_app"]

_WEB_UI = Path(__file__).resolve().parents[2] / "web_ui"
_STATIC_DIR = _WEB_UI / "static"
_SWAGGER_DIR = _WEB_UI / "vendor" / "node_modules" / "swagger-ui-dist"
_THREE_DIR = _WEB_UI / "vendor" / "node_modules" / "three"  # the 3D view's library (ES modules)


class CoreApp(FastAPI):
    """The core's FastAPI app. Plain service calls are forwarded before it, by the core's HTTP
    protocol (:mod:`services.core.gateway_protocol`), through :attr:`service_calls`; every request
    that reaches the app meets the edge checks first (:func:`edge_checks`: origin, body size)."""

    service_calls: ServiceCalls | None = None
    """The core's one service-call path, while the core runs (its HTTP protocol forwards through it)."""

    def __init__(self, *, max_message_bytes: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.max_message_bytes = max_message_bytes
        self._checked = edge_checks(super().__call__, max_message_bytes)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        await self._checked(scope, receive, send)


def create_app(settings: CoreSettings | None = None, *, endpoints: Sequence[ServedEndpoint] = ()) -> FastAPI:
    """The core as an ASGI app; ``settings.advertise_url`` (or host/port) is where nodes reach it.

    ``endpoints`` are the protocol endpoints plugged in from above (rosbridge, Foxglove: see
    :mod:`services.core.endpoint_servers`), each with the socket of its own port if it has one;
    ``skydeck core`` gives those of the table (:mod:`services.protocols.core_process`).
    """
    settings = settings or CoreSettings()
    fences = core_fences(settings)  # a class's files are read now: a bad one stops the start, in one line
    registry = Registry()
    core_url = settings.advertise_url or f"http://{reachable_host(settings.host)}:{settings.port}"
    core_node = CoreNode(registry, settings, core_url)
    servers = EndpointServers(settings, endpoints)
    rosparam = ParameterTree()  # ROS 1's parameter server: the core's, as roscore's

    @contextlib.asynccontextmanager
    async def lifespan(app: CoreApp) -> AsyncIterator[None]:
        http = HttpClient()
        core_node.start()
        app.state.rosout = RosoutLog(core_node)
        app.state.rosout.start()
        guests = Guests(registry, core_node.participant.url)
        calls = ServiceCalls(registry, guests, settings, http, fences)
        gateway = Gateway(registry, core_node, settings, http, calls, fences)
        app.state.http = http
        app.state.gateway = gateway
        app.state.calls = calls
        app.service_calls = calls
        app.state.recordings = Recordings(settings.recordings_folder, core_node, registry)
        await servers.start(CoreAccess(core_node, registry, guests, calls, gateway, settings, fences, rosparam))
        try:
            yield
        finally:
            app.service_calls = None
            await servers.stop()
            app.state.recordings.close()
            app.state.rosout.stop()
            core_node.stop()
            await http.aclose()

    app = CoreApp(
        title="Skydeck",
        description=(
            "Every command of the running system: each service of each live node is a POST at its "
            "name. Topics: GET the latest message, or open a WebSocket at the same path for the stream."
        ),
        version="0.1.0",
        docs_url=None,
        redoc_url=None,
        openapi_url=None,
        lifespan=lifespan,
        max_message_bytes=settings.max_message_bytes,
    )
    app.state.registry = registry
    app.state.settings = settings
    app.state.fences = fences
    app.state.core_node = core_node
    app.state.endpoints = servers
    app.state.rosparam = rosparam
    install_error_handlers(app)
    app.include_router(api_router)
    app.include_router(access_router)
    app.include_router(class_router)
    app.include_router(recordings_router)
    app.include_router(parameter_server_router)
    app.include_router(rosout_router)

    @app.get("/health", tags=["core"])
    async def health() -> dict[str, Any]:
        """Liveness of the core, and the ports of its protocol endpoints (by name)."""
        return {
            "status": "ok",
            "node": CORE_NODE,
            "pid": os.getpid(),
            "nodes": len(registry.nodes),
            "endpoints": servers.ports,
        }

    @app.websocket("/api/session")
    async def session(websocket: WebSocket) -> None:
        await serve_session(websocket, registry, fences)

    def core_topic(websocket: WebSocket) -> TopicPort:
        name = websocket.scope["path"].removeprefix(CORE_NODE_PATH)
        endpoint = core_node.endpoint(name)
        if endpoint is None or not endpoint.publishing:
            raise FrameRejected(Close.POLICY, f"the core does not publish {websocket.url.path}")
        guest = fences.admit(presented_token(websocket))
        return endpoint if guest.unlimited else FencedEndpoint(endpoint, guest)

    @app.get(CORE_NODE_PATH + "/health", include_in_schema=False)
    async def core_node_health() -> dict[str, Any]:
        return {"status": "ok", "node": CORE_NODE, "pid": os.getpid()}

    @app.get(CORE_NODE_PATH + "/{topic:path}", include_in_schema=False)
    async def core_latest(request: Request) -> Response:
        """The latest message of a topic the core publishes for its clients."""
        name = request.url.path.removeprefix(CORE_NODE_PATH)
        refusal = visitor(request).refusal(Verb.READ, name)
        if refusal is not None:
            return JSONResponse({"detail": str(refusal)}, status_code=refusal.http_status)
        endpoint = core_node.endpoint(name)
        if endpoint is None or not endpoint.publishing or endpoint.latest_frame is None:
            return JSONResponse({"detail": f"the core does not publish {request.url.path}"}, status_code=404)
        return Response(endpoint.latest_frame, media_type="application/json")

    @app.post(CORE_NODE_PATH + "/{name:path}", include_in_schema=False)
    async def core_service(request: Request) -> Response:
        """A service the core hosts for a guest (rosapi, a rosbridge client's), called directly."""
        name = request.scope["path"].removeprefix(CORE_NODE_PATH)
        reply = await request.app.state.calls.call_hosted(name, await request.body(), caller=visitor(request))
        return Response(reply.body, status_code=reply.status, media_type=reply.content_type)

    @app.websocket(CORE_NODE_PATH + "/{topic:path}")
    async def core_publication(websocket: WebSocket) -> None:
        """Nodes subscribed to a topic the core publishes (for its clients) link here."""
        await serve_topic_socket(websocket, core_topic, token="", stall_timeout_s=settings.reader_stall_s)

    @app.get("/openapi.json", include_in_schema=False)
    async def openapi(request: Request) -> JSONResponse:
        return JSONResponse(await aggregate_openapi(app.openapi(), registry, request.app.state.http))

    @app.get("/docs", include_in_schema=False)
    async def docs() -> HTMLResponse:
        return get_swagger_ui_html(
            openapi_url="/openapi.json",
            title="Skydeck — every command",
            swagger_js_url="/static/vendor/swagger-ui/swagger-ui-bundle.js",
            swagger_css_url="/static/vendor/swagger-ui/swagger-ui.css",
            swagger_favicon_url="/static/vendor/swagger-ui/favicon-32x32.png",
        )

    @app.get("/redoc", include_in_schema=False)
    async def redoc() -> RedirectResponse:
        return RedirectResponse("/docs")

    if _SWAGGER_DIR.is_dir():
        app.mount("/static/vendor/swagger-ui", StaticFiles(directory=_SWAGGER_DIR), name="swagger-ui")
    if _THREE_DIR.is_dir():
        app.mount("/static/vendor/three", StaticFiles(directory=_THREE_DIR), name="three")
    if _STATIC_DIR.is_dir():
        app.mount("/static", StaticFiles(directory=_STATIC_DIR), name="static")

    @app.get("/", include_in_schema=False)
    async def dashboard() -> Response:
        index = _STATIC_DIR / "index.html"
        if not index.is_file():
            return HTMLResponse("<p>The dashboard is not installed; the API is at <a href='/docs'>/docs</a>.</p>")
        return FileResponse(index)

    async def gateway_http(request: Request) -> Response:
        return await request.app.state.gateway.handle_http(request)  # type: ignore[no-any-return]

    async def gateway_stream(websocket: WebSocket) -> None:
        await websocket.app.state.gateway.handle_stream(websocket)

    for served in endpoints:  # an endpoint also on the core's own port (rosbridge's /rosbridge)
        if served.plugin.core_path is not None:
            app.router.routes.append(WebSocketRoute(served.plugin.core_path, _endpoint_route(servers, served.plugin.name)))

    # Last: every remaining path is a name.
    app.router.routes.append(Route("/{name:path}", gateway_http, methods=["GET", "POST"], include_in_schema=False))
    app.router.routes.append(WebSocketRoute("/{name:path}", gateway_stream))
    return app


def _endpoint_route(servers: EndpointServers, name: str) -> Callable[[WebSocket], Awaitable[None]]:
    async def serve(websocket: WebSocket) -> None:
        await servers.connections(name).serve(websocket)

    return serve
