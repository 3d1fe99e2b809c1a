"""A Foxglove connection's parameter ops: get, set, and updates as ``/parameter_events`` tells them.

Parameters are named with their node (``/control.max_speed``) and reach each node's own ROS 2
parameter services through :mod:`services.protocols.parameters`, with the connection's token
(so fenced as its calls are: a student reads and sets the parameters of their own nodes, and
is sent the updates of those alone).
"""

from __future__ import annotations

import json
from collections.abc import Awaitable, Callable
from typing import Any

from services.access import Verb
from services.protocols.foxglove.ops import ERROR, GetParameters, ParameterUpdates, SetParameters
from services.protocols.ops import Refused
from services.protocols.parameters import (
    ParameterError,
    Parameters,
    ParameterValueJson,
    event_values,
    split_name,
)
from services.protocols.session import ClientSession

__all__ = ["PARAMETER_EVENTS", "ParameterOps"]

PARAMETER_EVENTS = "/parameter_events"

Send = Callable[[dict[str, Any]], Awaitable[None]]


class ParameterOps:
    """One connection's parameter requests and the names whose updates it follows."""

    def __init__(self, session: ClientSession, send: Send, follow_events: Callable[[], None]) -> None:
        self._session = session
        self._send = send
        self._follow_events = follow_events  # (re)considers reading /parameter_events
        self._parameters = Parameters(session.access.registry, session.call)
        self._names: set[str] = set()
        self._all = False

    @property
    def wanted(self) -> bool:
        """Whether the client follows any parameter's updates."""
        return bool(self._names) or self._all

    async def get(self, op: GetParameters) -> None:
        try:
            values = await self._parameters.get(op.parameterNames or None)
        except ParameterError as error:
            await self._status(str(error))
            values = []
        await self._send_values(values, op.id)

    async def set(self, op: SetParameters) -> None:
        items = [ParameterValueJson(item.name, item.value, item.type) for item in op.parameters]
        try:
            results = await self._parameters.set(items)
        except ParameterError as error:
            raise Refused(str(error)) from None
        for name, successful, reason in results:
            if not successful:
                await self._status(f"{name} was not set: {reason}")
        if op.id is not None:
            try:
                values = await self._parameters.get([item.name for item in items])
            except ParameterError:
                values = []
            await self._send_values(values, op.id)

    def subscribe(self, op: ParameterUpdates) -> None:
        if op.parameterNames:
            self._names.update(op.parameterNames)
        else:
            self._all = True
        self._follow_events()

    def unsubscribe(self, op: ParameterUpdates) -> None:
        if op.parameterNames:
            self._names.difference_update(op.parameterNames)
        else:
            self._names.clear()
            self._all = False
        self._follow_events()

    def updates(self, frame: str) -> list[dict[str, Any]]:
        """The ``parameterValues`` message a ``/parameter_events`` frame makes for this client."""
        try:
            values = event_values(frame)
        except ValueError:
            return []
        visitor = self._session.visitor
        wanted = [
            v for v in values if (self._all or v.name in self._names) and visitor.allows(Verb.CALL, _get_service(v.name))
        ]
        if not wanted:
            return []
        text = json.dumps({"op": "parameterValues", "parameters": [_parameter(v) for v in wanted]})
        return [{"type": "websocket.send", "text": text}]

    async def _send_values(self, values: list[ParameterValueJson], request_id: Any) -> None:
        message: dict[str, Any] = {"op": "parameterValues", "parameters": [_parameter(v) for v in values]}
        if request_id is not None:
            message["id"] = request_id
        await self._send(message)

    async def _status(self, text: str) -> None:
        await self._send({"op": "status", "level": ERROR, "message": text})


def _get_service(name: str) -> str:
    """The service that reads the parameter ``name``: a client sees the updates of the
    parameters it may read (the fences' rule for them)."""
    return split_name(name)[0] + "/get_parameters"


def _parameter(value: ParameterValueJson) -> dict[str, Any]:
    entry: dict[str, Any] = {"name": value.name, "value": value.value}
    if value.type is not None:
        entry["type"] = value.type
    return entry
