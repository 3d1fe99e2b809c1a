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

    # A class (docs/security.md): its tokens file (`name,token` lines, `skydeck class` writes it)
    # and, optionally, its rules (what students share, YAML); each student's limits on what
    # enters the core through their token.
    class_tokens: Path | None = Field(default=None, description="the class's tokens file: one token per student")
    class_rules: Path | None = Field(default=None, description="the class's rules (YAML); default: services/access/policy.py")
    class_gradebook: Path | None = Field(default=None, description="the grades the class page shows (read when asked)")
    student_messages_per_s: float = Field(default=200.0, gt=0, description="messages a student's token may send a second")
    student_bytes_per_s: float = Field(default=float(1 << 20), gt=0, description="bytes a student's token may send a second")
    student_calls_in_flight: int = Field(default=16, ge=1, description="service calls of a student's token waiting at once")

    # Recordings made from the dashboard (`/api/recordings`); None: $XDG_DATA_HOME/skydeck/recordings.
    recordings_dir: Path | None = None

    @property
    def recordings_folder(self) -> Path:
        """``recordings_dir``, else ``$XDG_DATA_HOME/skydeck/recordings`` (``~/.local/share/...``)."""
        return self.recordings_dir or self.skydeck_data_dir / "recordings"
