"""The gateway: every topic and service name answered by the core, routed to the node behind it.

- ``POST /NAME``: a service call, forwarded to the hosting node (404 unknown, 503 unreachable,
  504 timeout, each with a ``detail`` that says what to do).
- ``GET /NAME``: the latest message of a topic, from a publisher.
- ``ws://CORE/NAME``: the topic's stream (see :mod:`services.core.relay`).
"""

from __future__ import annotations

from fastapi.responses import JSONResponse, Response
from starlette.requests import Request
from starlette.websockets import WebSocket

from services.core.registry import Registry
from services.core.relay import GATEWAY_NODE, Relays
from services.core.settings import CoreSettings
from services.runtime.auth import NOT_AUTHORISED, presented_token, token_matches
from services.runtime.http_client import HttpClient, HttpError, HttpTimeout
from services.runtime.outbox import Outbox
from services.runtime.stream import (
    CLOSE_BAD_OPTION,
    FrameRejected,
    StreamOptions,
    close_with,
    parse_frame,
    serve_stream,
)
from shared_models import (
    InvalidNameError,
    Message,
    UnknownInterfaceError,
    get_interface,
    resolve_name,
)

__all__ = ["Gateway"]

_FORWARDED_HEADERS = ("content-type", "authorization")


def _error(status_code: int, detail: str) -> JSONResponse:
    return JSONResponse({"detail": detail}, status_code=status_code)


class Gateway:
    """Routes names to nodes for HTTP and WebSocket clients of the core."""

    def __init__(self, registry: Registry, relays: Relays, settings: CoreSettings, http: HttpClient) -> None:
        self._registry = registry
        self._relays = relays
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
        found = self._registry.service(name)
        if found is None:
            if self._registry.topic_type(name) is not None:
                return _error(405, f"{name} is a topic, not a service: GET it or open a WebSocket to it")
            return _error(404, f"no service {name}: see `skydeck service list` or GET /api/graph")
        # Checked here as well as on the node: a call through the core is refused even when the
        # node behind it was started without the token.
        if not token_matches(self._settings.token, request):
            return _error(401, NOT_AUTHORISED)
        _, record = found
        node = record.description.name
        url = record.description.url.rstrip("/") + name
        headers = {key: value for key in _FORWARDED_HEADERS if (value := request.headers.get(key))}
        if token := presented_token(request):
            headers["authorization"] = f"Bearer {token}"  # also when it came as ?token= (a browser)
        try:
            reply = await self._http.post(
                url, await request.body(), headers=headers, timeout_s=self._settings.gateway_timeout_s
            )
        except ValueError:  # a ?token= with a line break: never put it into a header
            return _error(400, "the token holds characters a token cannot have")
        except HttpTimeout:
            return _error(
                504,
                f"{name} on node {node} did not answer within {self._settings.gateway_timeout_s:g} s: "
                f"is its handler stuck? see `skydeck node info {node}`",
            )
        except HttpError:
            return _error(
                503, f"node {node} hosting {name} is not reachable at {url}: is it running? see `skydeck node list`"
            )
        return Response(reply.body, status_code=reply.status, media_type=reply.headers.get("content-type"))

    async def _latest(self, name: str) -> Response:
        publication = self._relays.publications.get(name)
        if publication is not None and publication.latest_frame is not None:
            return Response(publication.latest_frame, media_type="application/json")
        publishers = [p for p in self._registry.publishers(name) if p.node != GATEWAY_NODE]
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
        """Relay a topic to one client, and publish what it sends (validated) to the topic."""
        await websocket.accept()
        try:
            topic = resolve_name(websocket.scope["path"])
            options = StreamOptions.from_query(dict(websocket.query_params))
            declared_type = self._declared_type(websocket.query_params.get("type"))
        except (InvalidNameError, FrameRejected) as error:
            code = error.code if isinstance(error, FrameRejected) else CLOSE_BAD_OPTION
            await close_with(websocket, code, str(error))
            return
        may_publish = token_matches(self._settings.token, websocket)
        published_type: type[Message] | None = None  # set by the first valid frame: then fixed

        def on_frame(text: str) -> None:
            nonlocal published_type
            if not may_publish:
                raise FrameRejected(CLOSE_BAD_OPTION, NOT_AUTHORISED)
            if published_type is not None:
                self._relays.publish(topic, parse_frame(published_type, published_type.__ros_type__, text))
                return
            msg_type = self._topic_type(topic, declared_type)
            msg = parse_frame(msg_type, msg_type.__ros_type__, text)  # before opening: a bad first frame opens nothing
            self._relays.open_publication(topic, msg_type)
            published_type = msg_type
            self._relays.publish(topic, msg)

        outbox = Outbox(options.outbox_size)
        initial_frame = self._relays.attach(topic, outbox)
        try:
            await serve_stream(websocket, outbox, options=options, initial_frame=initial_frame, on_frame=on_frame)
        finally:
            self._relays.detach(topic, outbox)
            if published_type is not None:
                self._relays.close_publication(topic)

    async def handle_gateway_publication(self, websocket: WebSocket) -> None:
        """A node links to a topic the gateway publishes (``/api/gateway/TOPIC``)."""
        await websocket.accept()
        topic = websocket.url.path.removeprefix("/api/gateway")
        publication = self._relays.publications.get(topic)
        if publication is None:
            await close_with(websocket, CLOSE_BAD_OPTION, f"the gateway does not publish {topic}")
            return
        try:
            options = StreamOptions.from_query(dict(websocket.query_params))
        except FrameRejected as rejected:
            await close_with(websocket, rejected.code, rejected.reason)
            return
        outbox = Outbox(options.outbox_size)
        publication.outboxes.add(outbox)
        try:
            await serve_stream(
                websocket, outbox, options=options, initial_frame=publication.latest_frame, on_frame=None
            )
        finally:
            publication.outboxes.discard(outbox)

    @staticmethod
    def _declared_type(type_name: str | None) -> type[Message] | None:
        if not type_name:
            return None
        try:
            declared = get_interface(type_name)
        except UnknownInterfaceError as error:
            raise FrameRejected(CLOSE_BAD_OPTION, str(error).splitlines()[0]) from None
        if not issubclass(declared, Message):
            raise FrameRejected(CLOSE_BAD_OPTION, f"{type_name} is a service type, not a message type")
        return declared

    def _topic_type(self, topic: str, declared: type[Message] | None) -> type[Message]:
        known = self._registry.topic_type(topic)
        if known is None:
            if declared is None:
                raise FrameRejected(
                    CLOSE_BAD_OPTION, f"{topic} has no type yet: add ?type=pkg/msg/Name to publish a new topic"
                )
            return declared
        if declared is not None and declared.__ros_type__ != known:
            raise FrameRejected(CLOSE_BAD_OPTION, f"{topic} is {known}, not {declared.__ros_type__}")
        try:
            msg_type = get_interface(known)
        except UnknownInterfaceError:
            raise FrameRejected(
                CLOSE_BAD_OPTION, f"the core does not know {known}: publish to the node directly"
            ) from None
        return msg_type  # type: ignore[return-value]
