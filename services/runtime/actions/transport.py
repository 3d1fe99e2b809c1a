"""How an action client reaches the graph: calls, subscriptions and "is the server there".

Two kinds of participant send goals: a node (the rclpy façade's ActionClient, ``skydeck action
send_goal``), whose calls go straight to the serving node, and the core (rosbridge's
``send_action_goal``), whose calls take the gateway's one call path and whose readings are taps
on its own node. :class:`ActionTransport` is what the client needs of either;
:class:`NodeTransport` is a node's, the core's is in its rosbridge adapter.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, Protocol

from shared_models import Message, ServiceType

if TYPE_CHECKING:
    from services.runtime.client import Client
    from services.runtime.node import Node

__all__ = ["ActionTransport", "NodeTransport"]

_FEEDBACK_DEPTH = 100  # generous: a client falling behind loses the oldest feedback first


class ActionTransport(Protocol):
    """What an action client needs of the participant it runs in."""

    async def call(self, service: str, srv_type: type[ServiceType], request: Message, timeout_s: float) -> Any:
        """The service's response; ServiceTimeoutError after ``timeout_s``, another
        ServiceError when it got no answer."""

    def subscribe(self, topic: str, msg_type: type[Message], callback: Callable[[Any], None]) -> None:
        """``callback(msg)`` for each message on ``topic`` (on the event loop), until closed."""

    async def served(self, services: Sequence[tuple[str, type[ServiceType]]]) -> bool:
        """Whether a node serves every one of ``services`` (name, type) now."""

    def linked(self, topic: str) -> bool:
        """Whether this participant receives ``topic`` from at least one publisher now."""

    def close(self) -> None:
        """Stop every subscription (the client is destroyed)."""


class NodeTransport:
    """An action client's way into the graph from a running SDK node."""

    def __init__(self, node: Node) -> None:
        self._node = node
        self._clients: dict[str, Client[Any]] = {}
        self._closed = False

    def _client(self, service: str, srv_type: type[ServiceType]) -> Client[Any]:
        client = self._clients.get(service)
        if client is None:
            client = self._clients[service] = self._node.create_client(srv_type, service)
        return client

    async def call(self, service: str, srv_type: type[ServiceType], request: Message, timeout_s: float) -> Any:
        return await self._client(service, srv_type).call(request, timeout_s=timeout_s)

    def subscribe(self, topic: str, msg_type: type[Message], callback: Callable[[Any], None]) -> None:
        def deliver(msg: Any) -> None:
            if not self._closed:
                callback(msg)

        self._node.create_subscription(msg_type, topic, deliver, _FEEDBACK_DEPTH)

    async def served(self, services: Sequence[tuple[str, type[ServiceType]]]) -> bool:
        for service, srv_type in services:
            if not await self._client(service, srv_type).service_is_ready():
                return False
        return True

    def linked(self, topic: str) -> bool:
        return self._node.is_linked(topic)

    def close(self) -> None:
        self._closed = True
