"""What ``skydeck launch`` reads of its environment, once, when it starts.

    SKYDECK_CORE_URL        where a running core is looked for first (as roslaunch looks at
                            ROS_MASTER_URI); without it, the launch's own core URL
    SKYDECK_<NAME>_PORT     a protocol endpoint's port, taken as given (not moved with the base port)

and the environment itself, which the launch hands on to every child (with ``SKYDECK_CORE_URL``
set to the launch's core) and offers to a roslaunch file's ``$(env NAME)`` and ``$(optenv ...)``.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from pydantic import PrivateAttr, create_model
from pydantic_settings import BaseSettings, SettingsConfigDict

from services.protocols.endpoints import ENDPOINTS, endpoint_port_fields
from services.runtime.settings import DEFAULT_CORE_URL

__all__ = ["LaunchSettings"]


class _Base(BaseSettings):
    model_config = SettingsConfigDict(env_prefix="SKYDECK_", extra="ignore")


if TYPE_CHECKING:  # the port fields are made at run time from the table of endpoints
    _WithGivenPorts = _Base
else:
    _WithGivenPorts = create_model("_WithGivenPorts", __base__=_Base, **endpoint_port_fields(given_only=True))


class LaunchSettings(_WithGivenPorts):
    """The launcher's settings (see the module docstring)."""

    core_url: str = DEFAULT_CORE_URL
    _environment: dict[str, str] = PrivateAttr(default_factory=lambda: dict(os.environ))

    @property
    def core_url_given(self) -> bool:
        """Whether ``SKYDECK_CORE_URL`` was set (else ``core_url`` is the default)."""
        return "core_url" in self.model_fields_set

    def endpoint_ports(self) -> dict[str, int]:
        """The endpoints' ports given by ``SKYDECK_*_PORT``, by endpoint name."""
        given = {endpoint.name: getattr(self, endpoint.setting) for endpoint in ENDPOINTS}
        return {name: port for name, port in given.items() if port is not None}

    @property
    def environment(self) -> dict[str, str]:
        """The environment the launch started in (a copy): what its children inherit."""
        return dict(self._environment)
