"""Settings of the core process, read from ``SKYDECK_*`` variables (flags map onto them)."""

from __future__ import annotations

from pydantic import Field
from pydantic_settings import BaseSettings, SettingsConfigDict

from services.runtime.settings import MAX_MESSAGE_BYTES

__all__ = ["CoreSettings"]


class CoreSettings(BaseSettings):
    """Where the core listens and how its gateway behaves."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_", extra="ignore")

    host: str = "127.0.0.1"
    port: int = Field(default=8000, ge=0, le=65535)
    # The URL nodes use to reach the core's gateway publications; derived from host/port if empty.
    advertise_url: str = ""
    token: str = ""

    # Gateway
    gateway_timeout_s: float = Field(default=10.0, gt=0, description="service calls through the gateway")
    # A topic published through the gateway stays advertised (and latched) this long after its
    # last publishing socket closed, so `topic pub --once` reaches subscribers that link late.
    gateway_linger_s: float = Field(default=2.0, ge=0)

    # Limits
    max_message_bytes: int = Field(default=MAX_MESSAGE_BYTES, gt=0)
    ping_interval_s: float = Field(default=5.0, gt=0)
    ping_timeout_s: float = Field(default=10.0, gt=0)

    log_level: str = "INFO"
