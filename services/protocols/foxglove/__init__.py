"""The Foxglove WebSocket protocol, for Foxglove and Lichtblick: the core's ``foxglove`` endpoint.

``PLUGIN`` is what the table of endpoints (:mod:`services.protocols.endpoints`) names: started
with the core, it serves connections on the endpoint's own port (8765). See docs/protocols.md.
"""

from __future__ import annotations

from services.core.endpoint_servers import EndpointPlugin
from services.protocols.foxglove.endpoint import FoxgloveEndpoint
from services.protocols.foxglove.ops import SUBPROTOCOLS

__all__ = ["PLUGIN", "SUBPROTOCOLS", "FoxgloveEndpoint"]

PLUGIN = EndpointPlugin(
    name="foxglove",
    start=FoxgloveEndpoint,
    greeting=(
        "Skydeck's Foxglove WebSocket endpoint: in Foxglove or Lichtblick, open a connection to "
        "ws://HOST:PORT. See docs/protocols.md.\n"
    ),
)
