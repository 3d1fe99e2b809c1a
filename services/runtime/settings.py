"""Settings of Skydeck's processes: one pydantic-settings source, read from ``SKYDECK_*``.

    ProcessSettings      what every server process has: where it listens, its token, its limits
    ├── NodeSettings     + how a node reaches the core, sim time, service-call timeout
    └── CoreSettings     (services.core.settings) + the gateway's timeouts and the endpoints' ports

Every field reads from the environment with the ``SKYDECK_`` prefix (``SKYDECK_PORT=8003``).
The CLI does not go through the environment: its flags become keyword arguments
(:func:`set_process_overrides`), which win over the environment, as pydantic-settings orders them.
"""

from __future__ import annotations

import argparse
import socket
from typing import Any, TypeVar

from pydantic import Field, ValidationError
from pydantic_settings import BaseSettings, SettingsConfigDict

from services.runtime.wire import MAX_MESSAGE_BYTES, STALL_CHECK_PERIOD_S

__all__ = [
    "DEFAULT_CORE_URL",
    "MAX_MESSAGE_BYTES",
    "NodeSettings",
    "ProcessSettings",
    "process_settings",
    "reachable_host",
    "set_process_overrides",
    "settings_from_flags",
]

DEFAULT_CORE_URL = "http://127.0.0.1:8000"

S = TypeVar("S", bound="ProcessSettings")
B = TypeVar("B", bound=BaseSettings)

# Flags of this process's command line (`skydeck run --port 8003 ...`), by field name.
_overrides: dict[str, Any] = {}


class ProcessSettings(BaseSettings):
    """Where a server process listens, its access token and its limits."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_", extra="ignore")

    # Where it listens: loopback unless told otherwise (containers pass 0.0.0.0).
    host: str = "127.0.0.1"
    port: int = Field(default=0, ge=0, le=65535, description="0 picks a free port")
    # The URL other processes use to reach it; derived from host/port when empty.
    advertise_url: str = ""
    token: str = ""

    # Limits
    max_message_bytes: int = Field(default=MAX_MESSAGE_BYTES, gt=0)
    # Keep-alive pings reap sockets whose peer vanished without closing.
    ping_interval_s: float = Field(default=5.0, gt=0)
    # Long enough for a reader that stalled (and was told so with 4001) to wake and read its
    # close frame: its pong waits behind the frames it has not read (docs/streams.md).
    ping_timeout_s: float = Field(default=30.0, gt=0)
    # A reader whose socket takes nothing for this long while frames wait is closed with 4001
    # (see reader_stall_s).
    stall_timeout_s: float = Field(default=5.0, gt=0)

    @property
    def reader_stall_s(self) -> float:
        """``stall_timeout_s``, kept shorter than ``ping_timeout_s``: a flooded reader's pong
        waits behind the frames it has not read, and the keepalive would otherwise drop it
        first, with no close frame to say why."""
        return min(self.stall_timeout_s, max(self.ping_timeout_s - 2 * STALL_CHECK_PERIOD_S, STALL_CHECK_PERIOD_S))

    log_level: str = "INFO"


class NodeSettings(ProcessSettings):
    """A node's settings: a process's, and how it reaches the core."""

    core_url: str = DEFAULT_CORE_URL
    use_sim_time: bool = False
    service_timeout_s: float = Field(default=10.0, gt=0)


def set_process_overrides(**values: Any) -> None:
    """Settings given on this process's command line; ``None`` values are left out."""
    _overrides.update({key: value for key, value in values.items() if value is not None})


def process_settings(cls: type[S], **defaults: Any) -> S:
    """``cls`` from its defaults, then ``defaults`` (a built-in node's port), then the
    environment, then the command line (:func:`set_process_overrides`)."""
    from_env = cls()
    explicit = {name: getattr(from_env, name) for name in from_env.model_fields_set}
    return cls(**{**defaults, **explicit, **{k: v for k, v in _overrides.items() if k in cls.model_fields}})


def reachable_host(host: str) -> str:
    """Where others reach a server listening on ``host``: 0.0.0.0 is where it listens, not an
    address, so the machine's name stands in (``--advertise-url`` says better)."""
    if host in ("0.0.0.0", "::", ""):
        return socket.gethostname()
    return host


def settings_from_flags(parser: argparse.ArgumentParser, settings_type: type[B], argv: list[str] | None) -> B:
    """A node's own settings: the flags given in ``argv`` over its ``SKYDECK_*`` variables; a
    bad value exits with the parser's one-line error naming the flag."""
    args = parser.parse_args(argv)
    overrides = {key: value for key, value in vars(args).items() if value is not None}
    try:
        return settings_type(**overrides)
    except ValidationError as error:
        first = error.errors()[0]
        flag = str(first["loc"][0]).replace("_", "-")
        parser.error(f"--{flag}: {first['msg']}")
