"""The table of protocol endpoints: the one place an endpoint is named, with its port.

    rosbridge   9090   --rosbridge-port   SKYDECK_ROSBRIDGE_PORT
    foxglove    8765   --foxglove-port    SKYDECK_FOXGLOVE_PORT

Everything that needs an endpoint reads this table: the settings of the ``skydeck core``
process (a port field per row, :mod:`.settings`), the process that plugs the endpoints into the
core (:mod:`.core_process`), ``skydeck core`` and ``skydeck launch``'s flags, the launch plan
and its port checks, ``skydeck doctor`` and the compose checks. A new protocol is a package
under ``services/protocols/`` and a row here.

The default ports are the tools' own (rosbridge_server's 9090, foxglove_bridge's 8765). A launch
on another base port moves them by as much as it moves the core (``--base-port 19340``: rosbridge
on 20430, Foxglove on 20105), so two launches side by side do not compete for them; a port given
by flag or ``SKYDECK_*_PORT`` is taken as given. 0 turns an endpoint's own port off.

This module imports nothing heavy: the launcher and the CLI read it without loading a protocol.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from pydantic import Field

if TYPE_CHECKING:
    from services.core.endpoint_servers import EndpointPlugin

__all__ = ["DEFAULT_BASE_PORT", "ENDPOINTS", "Endpoint", "endpoint_named", "endpoint_port_fields", "load_plugin"]

DEFAULT_BASE_PORT = 8000
"""The core's default port: the base at which every default port of the table holds."""

ENV_PREFIX = "SKYDECK_"


@dataclass(frozen=True)
class Endpoint:
    """One row of the table: a protocol endpoint of the core process."""

    name: str  # "rosbridge": names its flag, setting and environment variable
    default_port: int  # its port when the core is on DEFAULT_BASE_PORT (and for `skydeck core`)
    summary: str  # what it is for, as a flag's help says it
    plugin: str  # "package:NAME" of its EndpointPlugin, imported only by the process serving it

    @property
    def flag(self) -> str:
        """``--rosbridge-port``: the flag of ``skydeck core`` and ``skydeck launch``."""
        return f"--{self.name}-port"

    @property
    def setting(self) -> str:
        """``rosbridge_port``: the field of the core process's settings."""
        return f"{self.name}_port"

    @property
    def env_var(self) -> str:
        """``SKYDECK_ROSBRIDGE_PORT``: the environment variable of that setting."""
        return f"{ENV_PREFIX}{self.setting.upper()}"

    def port_at(self, base_port: int) -> int:
        """Its default port in a launch on ``base_port``: moved as far as the core is moved."""
        return self.default_port + base_port - DEFAULT_BASE_PORT


ENDPOINTS: tuple[Endpoint, ...] = (
    Endpoint(
        "rosbridge",
        9090,
        "rosbridge v2 endpoint for roslibjs/roslibpy",
        "services.protocols.rosbridge:PLUGIN",
    ),
    Endpoint(
        "foxglove",
        8765,
        "Foxglove WebSocket endpoint for Foxglove/Lichtblick",
        "services.protocols.foxglove:PLUGIN",
    ),
)


def endpoint_named(name: str) -> Endpoint:
    """The row called ``name`` (KeyError naming the known ones otherwise)."""
    for endpoint in ENDPOINTS:
        if endpoint.name == name:
            return endpoint
    raise KeyError(f"no endpoint {name!r}; the endpoints are {', '.join(e.name for e in ENDPOINTS)}")


def load_plugin(endpoint: Endpoint) -> EndpointPlugin:
    """Import the endpoint's protocol package and return its plugin."""
    module, _, attribute = endpoint.plugin.partition(":")
    plugin: EndpointPlugin = getattr(importlib.import_module(module), attribute)
    return plugin


def endpoint_port_fields(*, given_only: bool = False) -> dict[str, Any]:
    """A pydantic field per endpoint of the table, named by its ``setting`` (so read from its
    ``SKYDECK_*_PORT``): defaulting to its default port, or with ``given_only`` to None (the
    launcher, which moves a port nobody gave with the base port)."""
    return {
        endpoint.setting: (
            int | None if given_only else int,
            Field(
                default=None if given_only else endpoint.default_port,
                ge=0,
                le=65535,
                description=f"{endpoint.summary}; 0: off",
            ),
        )
        for endpoint in ENDPOINTS
    }
