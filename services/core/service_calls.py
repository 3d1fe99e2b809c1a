"""The one way a call reaches a service through the core, whoever asks.

``POST /NAME`` over HTTP and the protocol adapters' calls (rosbridge's ``call_service``,
Foxglove's service requests) all go through :meth:`ServiceCalls.start` (awaited:
:meth:`ServiceCalls.call`), so the same checks and the same failures apply to every caller, each
edge mapping them to its own reply:

    404  no service has that name (405: it is a topic)
    401  the write token is missing or wrong
    400  a token that cannot go into a header
    503  the hosting node cannot be reached
    504  it did not answer in time (the gateway timeout, or the caller's own)

A reply from the service, whatever its status (200, 422 for a bad request, 500 when the
handler raised), is handed back as it came. Services the core hosts for its guests (rosapi, a
rosbridge client's) are answered in-process by :meth:`ServiceCalls.call_hosted`, which the core
node's ``POST /api/core/NAME`` route uses too.
"""

from __future__ import annotations

import asyncio
import json
import logging
from collections.abc import Callable
from dataclasses import dataclass

from pydantic import ValidationError

from services.core.guests import Guests
from services.core.registry import Registry
from services.core.settings import CoreSettings
from services.runtime.auth import NOT_AUTHORISED, token_is_valid
from services.runtime.errors import ServiceError
from services.runtime.http_client import (
    Cancellable,
    HttpClient,
    HttpError,
    HttpReply,
    HttpTimeout,
    Outcome,
    outcome_of,
)
from shared_models.errors import SkydeckError

__all__ = ["CallOutcome", "ServiceCallFailed", "ServiceCalls", "ServiceReply", "error_reply"]

JSON = "application/json"
logger = logging.getLogger("skydeck.core")


@dataclass(frozen=True)
class ServiceReply:
    """What a service answered: HTTP status, body and its content type."""

    status: int
    body: bytes
    content_type: str | None = JSON

    @property
    def answered(self) -> bool:
        """Whether this is the service's response (a refusal with ``success: false`` is one)."""
        return self.status == 200

    def detail(self) -> str:
        """The reason a call was not answered, as one line (FastAPI's ``detail``, or the body)."""
        try:
            detail = json.loads(self.body)["detail"]
        except (ValueError, KeyError, TypeError):
            return self.body.decode(errors="replace")[:500]
        if isinstance(detail, list) and detail and isinstance(detail[0], dict):
            first = detail[0]
            where = ".".join(str(part) for part in first.get("loc", ()) if part != "body") or "(request)"
            return f"invalid request: {where}: {first.get('msg', '')}"
        return str(detail)


class ServiceCallFailed(ServiceError):
    """A call through the core that reached no service (the status says why, as HTTP does)."""

    def __init__(self, name: str, status: int, message: str) -> None:
        super().__init__(name, message)
        self.status = status

    @property
    def http_status(self) -> int:  # type: ignore[override]
        return self.status

    def reply(self) -> ServiceReply:
        """This failure as an HTTP caller gets it."""
        return error_reply(self.status, str(self))


CallOutcome = ServiceReply | ServiceCallFailed
"""What a call came to: the service's reply (of any status), or why none came."""


@dataclass(slots=True)
class _Target:
    """The node a call goes to, and the request's headers for it."""

    service: str
    node: str
    url: str
    headers: dict[str, str]

    def failed(self, error: Exception, timeout_s: float) -> ServiceCallFailed:
        """Why a call sent to the node got no reply (``error`` from the HTTP client)."""
        name, node = self.service, self.node
        if isinstance(error, ValueError):  # a ?token= with a line break: never put it into a header
            return ServiceCallFailed(name, 400, "the token holds characters a token cannot have")
        if isinstance(error, HttpTimeout):
            return ServiceCallFailed(
                name,
                504,
                f"{name} on node {node} did not answer within {timeout_s:g} s: "
                f"is its handler stuck? see `skydeck node info {node}`",
            )
        return ServiceCallFailed(
            name, 503, f"node {node} hosting {name} is not reachable at {self.url}: is it running? see `skydeck node list`"
        )


class ServiceCalls:
    """Routes a call to the node hosting the service (or answers it here for a guest)."""

    def __init__(self, registry: Registry, guests: Guests, settings: CoreSettings, http: HttpClient) -> None:
        self._registry = registry
        self._guests = guests
        self._settings = settings
        self._http = http
        self._hosted_calls: set[asyncio.Task[None]] = set()  # kept until they end: the loop holds tasks weakly

    def serves(self, name: str) -> bool:
        """Whether ``name`` is a registered service's (a POST to it is a call through the core)."""
        return self._registry.service(name) is not None

    async def call(
        self,
        name: str,
        body: bytes,
        *,
        token: str,
        timeout_s: float | None = None,
        content_type: str | None = JSON,
    ) -> ServiceReply:
        """Call service ``name`` with the request ``body`` (JSON; empty: the default request).

        Raises ServiceCallFailed when no service answered; see the module docstring.
        """
        outcome: CallOutcome = await outcome_of(
            lambda on_done: self.start(
                name, body, token=token, timeout_s=timeout_s, content_type=content_type, on_done=on_done
            )
        )
        if isinstance(outcome, ServiceCallFailed):
            raise outcome
        return outcome

    def start(
        self,
        name: str,
        body: bytes,
        *,
        token: str,
        on_done: Callable[[CallOutcome], None],
        timeout_s: float | None = None,
        content_type: str | None = JSON,
    ) -> Cancellable | None:
        """The call itself, :meth:`call` being it awaited: ``on_done`` gets the service's reply, or
        the ServiceCallFailed of why none came, once. For a service on a node it is called from
        the node reply's own I/O callback, with no task and no turn of the loop between (the core's
        HTTP connections forward calls so: a forwarded call's busiest path, docs/performance.md).
        Returns what cancels the call, if it is still out."""
        timeout_s = timeout_s or self._settings.gateway_timeout_s
        try:
            target = self._target(name, token=token, content_type=content_type)
        except ServiceCallFailed as failed:
            on_done(failed)
            return None
        if target is None:
            task = asyncio.get_running_loop().create_task(self._hosted(name, body, timeout_s, on_done))
            self._hosted_calls.add(task)
            task.add_done_callback(self._hosted_calls.discard)
            return task

        def replied(outcome: Outcome) -> None:
            on_done(_served(outcome) if isinstance(outcome, HttpReply) else target.failed(outcome, timeout_s))

        try:
            return self._http.start("POST", target.url, body, headers=target.headers, timeout_s=timeout_s, on_done=replied)
        except (ValueError, HttpError) as error:
            on_done(target.failed(error, timeout_s))
            return None

    def _target(self, name: str, *, token: str, content_type: str | None) -> _Target | None:
        """Where a call of ``name`` goes (None: a service hosted here), or ServiceCallFailed."""
        found = self._registry.service(name)
        if found is None:
            if self._registry.topic_type(name) is not None:
                raise ServiceCallFailed(name, 405, f"{name} is a topic, not a service: GET it or open a WebSocket to it")
            raise ServiceCallFailed(name, 404, f"no service {name}: see `skydeck service list` or GET /api/graph")
        # Checked here as well as on the node: a call through the core is refused even when the
        # node behind it was started without the token.
        if not token_is_valid(self._settings.token, token):
            raise ServiceCallFailed(name, 401, NOT_AUTHORISED)
        _, record = found
        if record.description.url == self._guests.url:
            return None
        headers = {"content-type": content_type} if content_type else {}
        if token:
            headers["authorization"] = f"Bearer {token}"  # also when it came as ?token= (a browser)
        return _Target(name, record.description.name, record.description.url.rstrip("/") + name, headers)

    async def _hosted(self, name: str, body: bytes, timeout_s: float, on_done: Callable[[CallOutcome], None]) -> None:
        try:
            reply = await self.call_hosted(name, body, timeout_s=timeout_s)
        except Exception:  # a fault of ours: said in the log, as uvicorn says an app's
            logger.exception("calling %s, hosted by the core, failed", name)
            reply = error_reply(500, f"{name} failed in the core: see its log")
        on_done(reply)

    async def call_hosted(self, name: str, body: bytes, *, timeout_s: float | None = None) -> ServiceReply:
        """Answer a call to a service the core hosts for a guest, as a node's route would."""
        timeout_s = timeout_s or self._settings.gateway_timeout_s
        service = self._guests.service(name)
        if service is None:
            return error_reply(404, f"no service {name}: see `skydeck service list`")
        try:
            request = service.srv_type.Request.model_validate_json(body or b"{}")
        except ValidationError as error:
            detail = [
                {"type": e["type"], "loc": ["body", *e["loc"]], "msg": e["msg"]}
                for e in error.errors(include_url=False, include_input=False)
            ]
            return ServiceReply(422, json.dumps({"detail": detail}).encode())
        try:
            async with asyncio.timeout(timeout_s):
                response = await service.handle(request, logger)
        except TimeoutError:
            return error_reply(504, f"{name} did not answer within {timeout_s:g} s")
        except SkydeckError as error:
            return error_reply(error.http_status, str(error))
        return ServiceReply(200, response.model_dump_json().encode())


def _served(reply: HttpReply) -> ServiceReply:
    """A node's reply, as it came."""
    return ServiceReply(reply.status, reply.body, reply.headers.get("content-type"))


def error_reply(status: int, detail: str) -> ServiceReply:
    """A reply saying why a call was not answered: FastAPI's ``{"detail": ...}`` with ``status``."""
    return ServiceReply(status, json.dumps({"detail": detail}).encode())
