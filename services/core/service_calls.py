"""The one way a call reaches a service through the core, whoever asks.

``POST /NAME`` over HTTP and the protocol adapters' calls (rosbridge's ``call_service``,
Foxglove's service requests) all go through :meth:`ServiceCalls.start` (awaited:
:meth:`ServiceCalls.call`), so the same checks and the same failures apply to every caller, each
edge mapping them to its own reply:

    404  no service has that name (405: it is a topic)
    401  no token, or one nobody has, where one is needed (:mod:`services.access.policy`)
    403  the caller's token may not call it (a student, outside their namespace; stopping
         another's node, resetting the world: :func:`~services.access.policy.service_verb`)
    429  the caller's token sends too much, or has too many calls waiting (a student: :mod:`services.access.rates`)
    400  a token that cannot go into a header
    503  the hosting node cannot be reached
    504  it did not answer in time (the gateway timeout, or the caller's own)

The caller is a :class:`~services.access.fences.Pass`: who it is, checked here before anything
is forwarded, so a call through the core is fenced even when the node behind it has no token.

A reply from the service, whatever its status (200, 422 for a bad request, 500 when the
handler raised), is handed back as it came. Services the core hosts for its guests (rosapi, a
rosbridge client's) are answered in-process by :meth:`ServiceCalls.call_hosted`, which the core
node's ``POST /api/core/NAME`` route uses too; while one runs, :data:`CALLER` is its caller (so
rosapi's parameter services act with the caller's rights, not the core's).
"""

from __future__ import annotations

import asyncio
import json
import logging
from collections.abc import Callable
from contextvars import ContextVar
from dataclasses import dataclass

from pydantic import ValidationError

from services.access import Fences, Pass, RateLimited, service_verb
from services.core.guests import Guests
from services.core.registry import Registry
from services.core.settings import CoreSettings
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

__all__ = ["CALLER", "CallOutcome", "ServiceCallFailed", "ServiceCalls", "ServiceReply", "error_reply"]

JSON = "application/json"
logger = logging.getLogger("skydeck.core")

CALLER: ContextVar[Pass] = ContextVar("skydeck_caller")
"""Who called the service the core is answering now (set while a hosted service's handler runs)."""


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

    def __init__(
        self, registry: Registry, guests: Guests, settings: CoreSettings, http: HttpClient, fences: Fences
    ) -> None:
        self.fences = fences  # the core's: a caller that comes with a token only is admitted by them
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
        caller: Pass,
        timeout_s: float | None = None,
        content_type: str | None = JSON,
    ) -> ServiceReply:
        """Call service ``name`` with the request ``body`` (JSON; empty: the default request).

        Raises ServiceCallFailed when no service answered; see the module docstring.
        """
        outcome: CallOutcome = await outcome_of(
            lambda on_done: self.start(
                name, body, caller=caller, timeout_s=timeout_s, content_type=content_type, on_done=on_done
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
        caller: Pass,
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
            target = self._target(name, body, caller=caller, content_type=content_type)
        except ServiceCallFailed as failed:
            on_done(failed)
            return None
        if target is None:
            task = asyncio.get_running_loop().create_task(self._hosted(name, body, caller, timeout_s, on_done))
            self._hosted_calls.add(task)
            task.add_done_callback(self._hosted_calls.discard)
            return task
        counted = None if caller.bucket is None else _Counted(caller)

        def replied(outcome: Outcome) -> None:
            if counted is not None:
                counted.end()
            on_done(_served(outcome) if isinstance(outcome, HttpReply) else target.failed(outcome, timeout_s))

        try:
            exchange = self._http.start("POST", target.url, body, headers=target.headers, timeout_s=timeout_s, on_done=replied)
        except (ValueError, HttpError) as error:
            _call_ended(caller)
            on_done(target.failed(error, timeout_s))
            return None
        if counted is None:
            return exchange
        counted.exchange = exchange
        return counted

    def _target(self, name: str, body: bytes, *, caller: Pass, content_type: str | None) -> _Target | None:
        """Where a call of ``name`` goes (None: a service hosted here), or ServiceCallFailed.

        Once it returns, the call is one of the caller's calls in flight (:func:`_call_ended`
        ends it)."""
        found = self._registry.service(name)
        if found is None:
            if self._registry.topic_type(name) is not None:
                raise ServiceCallFailed(name, 405, f"{name} is a topic, not a service: GET it or open a WebSocket to it")
            raise ServiceCallFailed(name, 404, f"no service {name}: see `skydeck service list` or GET /api/graph")
        _admit(name, body, caller)
        _, record = found
        if record.description.url == self._guests.url:
            return None
        headers = {"content-type": content_type} if content_type else {}
        # The node's session key where it has one: the call is admitted here, and the node, whose
        # own token may be another's (a student's node, called by the instructor), takes the
        # core's word for it. Else the caller's token (also when it came as ?token=: a browser).
        token = record.key or caller.token
        if token:
            headers["authorization"] = f"Bearer {token}"
        return _Target(name, record.description.name, record.description.url.rstrip("/") + name, headers)

    async def _hosted(
        self, name: str, body: bytes, caller: Pass, timeout_s: float, on_done: Callable[[CallOutcome], None]
    ) -> None:
        try:
            reply = await self._answer_hosted(name, body, caller=caller, timeout_s=timeout_s)
        except Exception:  # a fault of ours: said in the log, as uvicorn says an app's
            logger.exception("calling %s, hosted by the core, failed", name)
            reply = error_reply(500, f"{name} failed in the core: see its log")
        finally:
            _call_ended(caller)
        on_done(reply)

    async def call_hosted(self, name: str, body: bytes, *, caller: Pass) -> ServiceReply:
        """Answer a call to a service the core hosts for a guest, as a node's route would (its
        caller fenced as every call is)."""
        try:
            _admit(name, body, caller)
        except ServiceCallFailed as failed:
            return failed.reply()
        try:
            return await self._answer_hosted(name, body, caller=caller)
        finally:
            _call_ended(caller)

    async def _answer_hosted(
        self, name: str, body: bytes, *, caller: Pass, timeout_s: float | None = None
    ) -> ServiceReply:
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
        CALLER.set(caller)  # this task's: the handler's own calls act with the caller's rights
        try:
            async with asyncio.timeout(timeout_s):
                response = await service.handle(request, logger)
        except TimeoutError:
            return error_reply(504, f"{name} did not answer within {timeout_s:g} s")
        except SkydeckError as error:
            return error_reply(error.http_status, str(error))
        return ServiceReply(200, response.model_dump_json().encode())


def _admit(name: str, body: bytes, caller: Pass) -> None:
    """ServiceCallFailed (401, 403, 429) unless ``caller`` may call ``name`` with ``body`` now;
    a limited caller's call then counts as one in flight (:func:`_call_ended` ends it)."""
    if caller.unlimited:
        return
    verb, target = service_verb(name, body)
    refusal = caller.refusal(verb, target)
    if refusal is not None:
        raise ServiceCallFailed(name, refusal.http_status, str(refusal))
    bucket = caller.bucket
    if bucket is not None:
        try:
            bucket.spend(len(body))
            bucket.call_started()
        except RateLimited as limited:
            raise ServiceCallFailed(name, limited.http_status, str(limited)) from None


def _call_ended(caller: Pass) -> None:
    if caller.bucket is not None:
        caller.bucket.call_ended()


class _Counted:
    """A limited caller's call under way, ended once as one of the caller's calls in flight: by
    its reply, or by a cancel (after which no reply comes)."""

    __slots__ = ("_caller", "exchange")

    def __init__(self, caller: Pass) -> None:
        self._caller: Pass | None = caller
        self.exchange: Cancellable | None = None

    def end(self) -> None:
        if self._caller is not None:
            _call_ended(self._caller)
            self._caller = None

    def cancel(self) -> None:
        if self.exchange is not None:
            self.exchange.cancel()
        self.end()


def _served(reply: HttpReply) -> ServiceReply:
    """A node's reply, as it came."""
    return ServiceReply(reply.status, reply.body, reply.headers.get("content-type"))


def error_reply(status: int, detail: str) -> ServiceReply:
    """A reply saying why a call was not answered: FastAPI's ``{"detail": ...}`` with ``status``."""
    return ServiceReply(status, json.dumps({"detail": detail}).encode())
