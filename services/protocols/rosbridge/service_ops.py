"""One rosbridge connection's services: the calls it makes and the services it hosts.

``call_service`` takes the HTTP gateway's one call path and always ends with one
``service_response``: the answer with ``result: true``, or ``result: false`` and the reason in
``values`` (no service, no answer within its ``timeout`` or the gateway's, no token), and nothing
else, as rosbridge_server answers. ``args`` may be an object or a list in field order; ``id``
comes back; ``fragment_size`` and ``compression`` (``png``) shape the response.

A service the client advertises (``advertise_service``) is hosted by the core for it, so nodes,
``curl`` and other clients call it like any other: each call reaches the client as a
``call_service`` with an id, and its ``service_response`` with that id answers it. As
rosbridge_suite reads that response, ``values`` is the answer even when ``result`` is false
(roslibpy sends the response it has either way); a response with ``result: false`` and no
object in ``values`` (roslibjs's failed callback: nothing, or the error's text) fails the call
with that text.
"""

from __future__ import annotations

import asyncio
import itertools
import json
import logging
from typing import Any

from pydantic import ValidationError

from services.access import Verb
from services.protocols.ops import Refused, describe_error
from services.protocols.rosbridge.frames import Replies, Status
from services.protocols.rosbridge.ops import (
    AdvertiseService,
    CallService,
    ServiceResponse,
    UnadvertiseService,
    request_body,
)
from services.protocols.session import ClientSession
from services.runtime.errors import ServiceUnavailableError
from services.runtime.service import ServiceHandlerError
from shared_models import Message, ServiceType, get_interface, resolve_name
from shared_models.errors import SkydeckError

__all__ = ["ConnectionServices"]

_MAX_CALLS_IN_FLIGHT = 256


class ConnectionServices:
    """A connection's service calls in flight and hosted services (see the module docstring)."""

    def __init__(self, session: ClientSession, replies: Replies, status: Status) -> None:
        self._session = session
        self._replies = replies
        self._status = status
        self._hosted: dict[str, _ClientService] = {}
        self._calls: set[asyncio.Task[None]] = set()

    def close(self) -> None:
        for task in self._calls:
            task.cancel()
        for service in self._hosted.values():
            service.fail_pending(f"the rosbridge client hosting {service.name} disconnected")

    # -- calling --------------------------------------------------------------------------------

    async def call_service(self, op: CallService) -> None:
        if len(self._calls) >= _MAX_CALLS_IN_FLIGHT:
            raise Refused(f"{_MAX_CALLS_IN_FLIGHT} service calls are already in flight on this connection")
        task = asyncio.get_running_loop().create_task(self._answer_call(op))
        self._calls.add(task)
        task.add_done_callback(self._calls.discard)

    async def _answer_call(self, op: CallService) -> None:
        values: Any
        name = op.service
        try:
            Replies.check(op.compression)
            name = resolve_name(op.service)
            body = request_body(op.args, self._request_type(name, op.type))
            reply = await self._session.call(name, body, timeout_s=op.timeout)
            if reply.answered:
                values, result = json.loads(reply.body), True
            else:
                values, result = reply.detail(), False
        except (SkydeckError, ValueError) as error:
            values, result = str(error), False
        # A failure is this response alone, as rosbridge_server sends it (it logs the error on its
        # side and sends no `status`, for which roslibpy has no handler: issue 32).
        response: dict[str, Any] = {"op": "service_response", "service": name, "values": values, "result": result}
        if op.id is not None:
            response["id"] = op.id
        compression = op.compression if op.compression in (None, "none", "png") else None
        for text in self._replies.texts(response, compression=compression, fragment_size=op.fragment_size, label=name):
            await self._session.send_text(text)

    def _request_type(self, name: str, given: str | None) -> type[Message] | None:
        """The request type of service ``name`` (to read positional ``args``), if known."""
        type_name = given
        found = self._session.access.registry.service(name)
        if found is not None:
            type_name = found[0].type
        if not type_name:
            return None
        try:
            srv = get_interface(type_name)
        except SkydeckError:
            return None
        return srv.Request if isinstance(srv, type) and issubclass(srv, ServiceType) else None

    # -- hosting --------------------------------------------------------------------------------

    async def advertise_service(self, op: AdvertiseService) -> None:
        name = resolve_name(op.service)
        self._session.visitor.check(Verb.SERVE, name)
        srv = get_interface(op.type)
        if not (isinstance(srv, type) and issubclass(srv, ServiceType)):
            raise Refused(f"{op.type} is a message type, not a service type")
        found = self._session.access.registry.service(name)
        if found is not None and name not in self._hosted:
            raise Refused(f"{name} is already served by {found[1].description.name}")
        service = self._hosted.get(name)
        if service is not None:
            service.fail_pending(f"{name} was advertised again")
        self._hosted[name] = service = _ClientService(name, srv, self._session)
        self._session.guest.serves(service)
        await self._status("info", f"serving {name} ({op.type})", op.id)

    async def unadvertise_service(self, op: UnadvertiseService) -> None:
        name = resolve_name(op.service)
        service = self._hosted.pop(name, None)
        if service is None:
            await self._status("warning", f"{name} is not served by this client", op.id)
            return
        service.fail_pending(f"{name} was unadvertised")
        self._session.guest.stops_serving(name)

    async def service_response(self, op: ServiceResponse) -> None:
        name = resolve_name(op.service)
        service = self._hosted.get(name)
        if service is None or not service.answer(op):
            raise Refused(f"no call {op.id!r} to {name} is waiting for an answer")


class _ClientService:
    """A service a rosbridge client hosts: the core forwards each call to it as ``call_service``
    and waits for its ``service_response`` (the caller's timeout applies: 504 if none comes)."""

    def __init__(self, name: str, srv_type: type[ServiceType], session: ClientSession) -> None:
        self.name = name
        self.srv_type = srv_type
        self._session = session
        self._ids = itertools.count(1)
        self._pending: dict[str, asyncio.Future[ServiceResponse]] = {}

    async def handle(self, request: Message, logger: logging.Logger) -> Message:
        call_id = f"service_request:{self.name}:{next(self._ids)}"
        future: asyncio.Future[ServiceResponse] = asyncio.get_running_loop().create_future()
        self._pending[call_id] = future
        try:
            await self._session.send_text(json.dumps({
                "op": "call_service",
                "id": call_id,
                "service": self.name,
                "args": request.model_dump(mode="json"),
            }))  # fmt: skip
            answer = await future
        finally:
            self._pending.pop(call_id, None)
        if not answer.result and not isinstance(answer.values, dict):
            reason = f": {answer.values}" if answer.values else ""
            raise ServiceHandlerError(f"the rosbridge client serving {self.name} failed{reason}")
        try:
            return self.srv_type.Response.model_validate(answer.values if answer.values is not None else {})
        except ValidationError as error:
            raise ServiceHandlerError(
                f"the rosbridge client serving {self.name} answered {describe_error('service_response', error)}"
            ) from None

    def answer(self, op: ServiceResponse) -> bool:
        future = self._pending.get(str(op.id))
        if future is None or future.done():
            return False
        future.set_result(op)
        return True

    def fail_pending(self, reason: str) -> None:
        for future in self._pending.values():
            if not future.done():
                future.set_exception(ServiceUnavailableError(self.name, reason))
