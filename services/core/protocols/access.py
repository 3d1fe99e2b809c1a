"""What a protocol adapter may use of the core: one object handed to every connection.

Topics go through the core node (:class:`~services.core.gateway_topic.GatewayTopic`), service
calls through the one call path (:class:`~services.core.service_calls.ServiceCalls`), and each
connection is a guest in the graph. The registry is read, never written, by adapters.
"""

from __future__ import annotations

from dataclasses import dataclass

from starlette.websockets import WebSocket

from services.core.core_node import CoreNode
from services.core.gateway import Gateway
from services.core.guests import Guests
from services.core.protocols.session import ClientSession
from services.core.registry import Registry
from services.core.service_calls import ServiceCalls
from services.core.settings import CoreSettings

__all__ = ["CoreAccess"]


@dataclass(frozen=True)
class CoreAccess:
    """The core's parts a protocol connection uses (see the module docstring)."""

    core: CoreNode
    registry: Registry
    guests: Guests
    calls: ServiceCalls
    gateway: Gateway
    settings: CoreSettings

    def session(self, websocket: WebSocket, protocol: str) -> ClientSession:
        """A new connection of ``protocol`` ("rosbridge", "foxglove"), shown in the graph as
        ``/PROTOCOL_client_N``."""
        peer = f"{websocket.client.host}:{websocket.client.port}" if websocket.client else "?"
        guest = self.guests.add(f"/{protocol}_client", client=f"{protocol} client {peer}", numbered=True)
        return ClientSession(self, websocket, guest)
