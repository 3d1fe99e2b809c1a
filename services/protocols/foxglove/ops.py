"""The Foxglove WebSocket protocol's messages: the JSON ops a client sends, and the binary opcodes.

Each JSON op is a pydantic model read by :class:`~services.protocols.ops.JsonOps` (a bad field
is named in the ``status`` reply); fields a model does not name are ignored. Binary messages
start with an opcode: the client's ``0x01`` message data and ``0x02`` service call requests,
the server's ``0x01`` message data, ``0x02`` time and ``0x03`` service call responses. Field
names are the protocol's own (camelCase).
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field

from services.protocols.ops import Op

__all__ = [
    "CLIENT_MESSAGE",
    "ERROR",
    "MESSAGE_DATA",
    "SERVICE_REQUEST",
    "SERVICE_RESPONSE",
    "SUBPROTOCOLS",
    "TIME",
    "Advertise",
    "ClientChannel",
    "ConnectionGraph",
    "GetParameters",
    "ParameterUpdates",
    "SetParameters",
    "Subscribe",
    "Unadvertise",
    "Unsubscribe",
]

SUBPROTOCOLS = ("foxglove.websocket.v1", "foxglove.sdk.v1")
INFO, WARNING, ERROR = 0, 1, 2  # a status's level
MESSAGE_DATA, TIME, SERVICE_RESPONSE = 1, 2, 3  # server -> client binary opcodes
CLIENT_MESSAGE, SERVICE_REQUEST = 1, 2  # client -> server binary opcodes

Uint32 = Annotated[int, Field(ge=0, lt=2**32)]
RequestId = str | int | None


class _Item(BaseModel):
    model_config = ConfigDict(extra="ignore", strict=True)


class SubscriptionItem(_Item):
    id: Uint32
    channelId: Uint32


class Subscribe(Op):
    subscriptions: list[SubscriptionItem]


class Unsubscribe(Op):
    subscriptionIds: list[int]


class ClientChannel(_Item):
    id: Uint32
    topic: str
    encoding: str
    schemaName: str | None = None


class Advertise(Op):
    channels: list[ClientChannel]


class Unadvertise(Op):
    channelIds: list[int]


class GetParameters(Op):
    parameterNames: list[str] | None = None  # None or empty: every parameter
    id: RequestId = None


class ParameterItem(_Item):
    name: str
    value: Any = None
    type: str | None = None


class SetParameters(Op):
    parameters: list[ParameterItem]
    id: RequestId = None


class ParameterUpdates(Op):
    """``subscribeParameterUpdates`` and ``unsubscribeParameterUpdates``."""

    parameterNames: list[str] | None = None  # None or empty: every parameter


class ConnectionGraph(Op):
    """``subscribeConnectionGraph`` and ``unsubscribeConnectionGraph``."""
