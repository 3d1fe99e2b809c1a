"""Settings of the core process: a process's (``ProcessSettings``), the gateway's own, and the
ports of the protocol endpoints it serves beside its own (rosbridge, Foxglove)."""

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

    # Protocol endpoints, each on a port of its own (0 turns it off), at the defaults of the tools
    # users already have: rosbridge_server's 9090 and foxglove_bridge's 8765. rosbridge is also
    # at /rosbridge on the core's own port, whatever this says.
    rosbridge_port: int = Field(default=9090, ge=0, le=65535, description="rosbridge v2 endpoint; 0: off")
    foxglove_port: int = Field(default=8765, ge=0, le=65535, description="Foxglove WebSocket endpoint; 0: off")
    # Recordings made from the dashboard (`/api/recordings`); None: $XDG_DATA_HOME/skydeck/recordings.
    recordings_dir: Path | None = None
