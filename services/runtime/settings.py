"""Settings of Skydeck's processes: one pydantic-settings object per process, from ``SKYDECK_*``.

    ProcessSettings      what every server process has: where it listens, its token, its limits,
    │                    where it keeps files (the XDG base directories)
    ├── NodeSettings     + how a node reaches the core, sim time, service-call timeout, ROS_NAMESPACE
    └── CoreSettings     (services.core.settings) + the gateway's; CoreProcessSettings
                         (services.protocols.settings) + each protocol endpoint's port

Every field reads from the environment with the ``SKYDECK_`` prefix (``SKYDECK_PORT=8003``);
another tool's variables that Skydeck honours (``ROS_NAMESPACE``, ``XDG_STATE_HOME``,
``XDG_DATA_HOME``) are read here too, as fields, and nowhere else. A process's entry point builds
its settings once, its command line's flags over the environment (:meth:`ProcessSettings.from_flags`:
keyword arguments win over the environment, as pydantic-settings orders them), and passes them
down: ``skydeck core`` to the core's app factory, ``skydeck run`` to every node of the process
(:func:`use_node_settings`; a node made without settings takes them, :func:`node_settings`, as
a ROS node takes its process's context).
"""

from __future__ import annotations

import argparse
import socket
from pathlib import Path
from typing import Any, TypeVar

from pydantic import Field, ValidationError
from pydantic_settings import BaseSettings, SettingsConfigDict

from services.runtime.wire import MAX_MESSAGE_BYTES, STALL_CHECK_PERIOD_S

__all__ = [
    "DEFAULT_CORE_URL",
    "MAX_MESSAGE_BYTES",
    "NodeSettings",
    "ProcessSettings",
    "node_settings",
    "reachable_host",
    "settings_from_flags",
    "use_node_settings",
]

DEFAULT_CORE_URL = "http://127.0.0.1:8000"

S = TypeVar("S", bound="ProcessSettings")
B = TypeVar("B", bound=BaseSettings)


class ProcessSettings(BaseSettings):
    """Where a server process listens, its access token and its limits."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_", extra="ignore", populate_by_name=True)

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

    # Where Skydeck keeps files on this machine: the XDG base directories (their own variables,
    # unprefixed), under ~/.local when unset.
    state_dir: str = Field(default="", description="empty: $XDG_STATE_HOME/skydeck")
    xdg_state_home: str = Field(default="", validation_alias="XDG_STATE_HOME")
    xdg_data_home: str = Field(default="", validation_alias="XDG_DATA_HOME")

    @property
    def skydeck_state_dir(self) -> Path:
        """``SKYDECK_STATE_DIR``, else ``$XDG_STATE_HOME/skydeck``, else ``~/.local/state/skydeck``."""
        if self.state_dir:
            return Path(self.state_dir)
        return Path(self.xdg_state_home or Path.home() / ".local" / "state") / "skydeck"

    @property
    def skydeck_data_dir(self) -> Path:
        """``$XDG_DATA_HOME/skydeck``, else ``~/.local/share/skydeck``."""
        return Path(self.xdg_data_home or Path.home() / ".local" / "share") / "skydeck"

    @classmethod
    def from_flags(cls: type[S], **flags: Any) -> S:
        """These settings from a command line's flags (``None``: not given) over the environment."""
        return cls(**{name: value for name, value in flags.items() if value is not None})

    def with_default_port(self: S, port: int) -> S:
        """These settings, listening on ``port`` unless a port was given (flag or environment):
        a built-in node's own port (``skydeck run control``: 8003)."""
        return self if "port" in self.model_fields_set else self.model_copy(update={"port": port})


class NodeSettings(ProcessSettings):
    """A node's settings: a process's, and how it reaches the core."""

    core_url: str = DEFAULT_CORE_URL
    use_sim_time: bool = False
    service_timeout_s: float = Field(default=10.0, gt=0)
    # A lockstep run's coordinator (services.runtime.lockstep): set by `skydeck grade` for the
    # processes it starts, so that the world waits for their nodes; empty: run free.
    lockstep_url: str = ""
    # How long the node waits for the core quietly before saying it waits: a launch that starts
    # a node beside its core (both starting) sets it; 0 says so at the first refused connection.
    core_start_grace_s: float = Field(default=0.0, ge=0)
    # ROS 1's variable for the namespace a rospy program's node starts in (`ROS_NAMESPACE=/robot1`).
    ros_namespace: str = Field(default="", validation_alias="ROS_NAMESPACE")


_this_process: NodeSettings | None = None


def use_node_settings(settings: NodeSettings | None) -> None:
    """Make ``settings`` this process's node settings (None: none): what ``skydeck run`` built
    from its flags over the environment, for every node the process makes without its own."""
    global _this_process
    _this_process = settings


def node_settings() -> NodeSettings:
    """This process's node settings (:func:`use_node_settings`); a program started without
    ``skydeck run`` (``python3 node.py``, a test) has none set, and reads the environment now."""
    return _this_process if _this_process is not None else NodeSettings()


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
