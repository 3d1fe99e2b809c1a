"""The ``skydeck core`` process's settings: the core's, and one port per endpoint of the table.

    CoreProcessSettings(rosbridge_port=0)        # or SKYDECK_ROSBRIDGE_PORT=0, --rosbridge-port 0

The port fields are made from :data:`~services.protocols.endpoints.ENDPOINTS` (a row's
``setting``, its ``default_port``), so a new endpoint needs no line here; code reads them with
:meth:`CoreProcessSettings.endpoint_port`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pydantic import create_model

from services.core.settings import CoreSettings
from services.protocols.endpoints import Endpoint, endpoint_port_fields

__all__ = ["CoreProcessSettings"]


if TYPE_CHECKING:  # the fields are made at run time; the type checker sees the core's settings
    _WithEndpointPorts = CoreSettings
else:
    _WithEndpointPorts = create_model("_WithEndpointPorts", __base__=CoreSettings, **endpoint_port_fields())


class CoreProcessSettings(_WithEndpointPorts):
    """Where the core listens, how its gateway behaves, and each endpoint's own port (0: off)."""

    def endpoint_port(self, endpoint: Endpoint) -> int:
        """The port ``endpoint`` listens on (0: not on a port of its own)."""
        port: int = getattr(self, endpoint.setting)
        return port
