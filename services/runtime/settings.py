"""Settings of a node process: one pydantic-settings class, read from ``SKYDECK_*`` variables."""

from __future__ import annotations

import argparse
import os
import socket
from typing import TypeVar

from pydantic import Field, ValidationError
from pydantic_settings import BaseSettings, SettingsConfigDict

__all__ = [
    "DEFAULT_CORE_URL",
    "MAX_MESSAGE_BYTES",
    "NodeSettings",
    "reachable_host",
    "settings_from_flags",
    "settings_with_default_port",
]

S = TypeVar("S", bound=BaseSettings)

DEFAULT_CORE_URL = "http://127.0.0.1:8000"
# Frames and bodies above this are refused (WebSocket close 1009, HTTP 413): a camera frame is
# ~20 KiB, so 1 MiB leaves room while bounding what one client can make a node buffer.
MAX_MESSAGE_BYTES = 1 << 20


class NodeSettings(BaseSettings):
    """Where a node listens, how it reaches the core, and its limits.

    Every field reads from the environment with the ``SKYDECK_`` prefix (``SKYDECK_PORT=8003``);
    ``skydeck run`` maps its flags onto the same variables.
    """

    model_config = SettingsConfigDict(env_prefix="SKYDECK_", extra="ignore")

    # Where the node listens: loopback unless told otherwise (containers pass 0.0.0.0).
    host: str = "127.0.0.1"
    port: int = Field(default=0, ge=0, le=65535, description="0 picks a free port")
    # The URL other processes use to reach this node; derived from host/port when empty.
    advertise_url: str = ""
    core_url: str = DEFAULT_CORE_URL
    token: str = ""
    use_sim_time: bool = False

    # Limits
    max_message_bytes: int = Field(default=MAX_MESSAGE_BYTES, gt=0)
    # Keep-alive pings reap sockets whose peer vanished without closing.
    ping_interval_s: float = Field(default=5.0, gt=0)
    ping_timeout_s: float = Field(default=10.0, gt=0)
    service_timeout_s: float = Field(default=10.0, gt=0)

    log_level: str = "INFO"


def settings_with_default_port(default_port: int) -> NodeSettings:
    """Settings for a built-in node: its well-known port unless ``SKYDECK_PORT`` says otherwise."""
    if "SKYDECK_PORT" in os.environ:
        return NodeSettings()
    return NodeSettings(port=default_port)


def reachable_host(host: str) -> str:
    """Where others reach a server listening on ``host``: 0.0.0.0 is where it listens, not an
    address, so the machine's name stands in (``--advertise-url`` says better)."""
    if host in ("0.0.0.0", "::", ""):
        return socket.gethostname()
    return host


def settings_from_flags(parser: argparse.ArgumentParser, settings_type: type[S], argv: list[str] | None) -> S:
    """A node's own settings: the flags given in ``argv`` over its ``SKYDECK_*`` variables; a
    bad value exits with the parser's one-line error naming the flag."""
    args = parser.parse_args(argv)
    overrides = {key: value for key, value in vars(args).items() if value is not None}
    try:
        return settings_type(**overrides)
    except ValidationError as error:
        first = error.errors()[0]
        parser.error(f"--{first['loc'][0]}: {first['msg']}")
