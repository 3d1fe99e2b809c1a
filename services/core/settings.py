"""Settings of the core: a process's (``ProcessSettings``) and the gateway's own.

The protocol endpoints' ports are not the core's: ``skydeck core`` runs with
:class:`services.protocols.settings.CoreProcessSettings`, these and one port per endpoint.
"""

from __future__ import annotations

from pathlib import Path

from pydantic import Field

from services.runtime.settings import ProcessSettings

__all__ = ["CoreSettings"]


class CoreSettings(ProcessSettings):
    """Where the core listens and how its gateway behaves."""

    port: int = Field(default=8000, ge=0, le=65535)

    # Gateway
    gateway_timeout_s: float = Field(default=10.0, gt=0, description="service calls through the gateway")
    # A topic published through the gateway stays advertised (and latched) this long after its
    # last publishing socket closed, so `topic pub --once` reaches subscribers that link late.
    gateway_linger_s: float = Field(default=2.0, ge=0)

    # Recordings made from the dashboard (`/api/recordings`); None: $XDG_DATA_HOME/skydeck/recordings.
    recordings_dir: Path | None = None

    @property
    def recordings_folder(self) -> Path:
        """``recordings_dir``, else ``$XDG_DATA_HOME/skydeck/recordings`` (``~/.local/share/...``)."""
        return self.recordings_dir or self.skydeck_data_dir / "recordings"
