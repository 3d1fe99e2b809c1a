"""From a launch file and the command line's options to the exact processes to start.

>>> from services.launch.spec import default_launch_file, load_launch_file
>>> spec = load_launch_file(default_launch_file())
>>> plans = plan_launch(spec, LaunchOptions(base_port=9000, seed=7, exclude=("ai",)))
>>> [(plan.name, plan.port) for plan in plans]
[('core', 9000), ('sim', 9001), ('perception', 9002), ('control', 9003)]
>>> plans[1].args
('--speed', '1', '--seed', '7', '--boxes', '8')
"""

from __future__ import annotations

import dataclasses
import math
import random
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field

from services.core.settings import CoreSettings
from services.launch.errors import LaunchError
from services.launch.spec import LaunchSpec, NodeSpec
from sim_server.worlds import WORLDS, default_world, world_options  # the table only: no PyBullet

__all__ = [
    "DEFAULT_BASE_PORT",
    "LaunchOptions",
    "NodePlan",
    "core_url",
    "default_command",
    "plan_launch",
]

DEFAULT_BASE_PORT = 8000
# The core's protocol endpoints: the flag of `skydeck core`, and the field of both LaunchOptions
# and CoreSettings (which holds the defaults and reads SKYDECK_<FIELD>).
_ENDPOINTS = (("--rosbridge-port", "rosbridge_port"), ("--foxglove-port", "foxglove_port"))
_MAX_SEED = 2**32 - 1


@dataclass(frozen=True)
class LaunchOptions:
    """The options of ``skydeck launch``; ``None`` means the default (a drawn seed). The
    worlds' own options (``--boxes``, ``--robots``: :func:`sim_server.worlds.world_options`) are
    in ``world_options``, by name; one not given is its world's default."""

    base_port: int = DEFAULT_BASE_PORT
    speed: str = "1"
    seed: int | None = None
    exclude: tuple[str, ...] = ()
    world_options: Mapping[str, int] = field(default_factory=dict)
    # The core's protocol endpoints (0: off; None: the core's setting, SKYDECK_ROSBRIDGE_PORT or
    # 9090); not shifted by --base-port: they are the ports the tools' users already know.
    rosbridge_port: int | None = None
    foxglove_port: int | None = None

    def __post_init__(self) -> None:
        if not 1 <= self.base_port <= 65535:
            raise LaunchError(f"--base-port must be a port number 1-65535, got {self.base_port}")
        for flag, port in (("--rosbridge-port", self.rosbridge_port), ("--foxglove-port", self.foxglove_port)):
            if port is not None and not 0 <= port <= 65535:
                raise LaunchError(f"{flag} must be a port number 0-65535 (0: off), got {port}")
        if self.speed != "max":
            try:
                speed = float(self.speed)
            except ValueError:
                speed = math.nan
            if not (math.isfinite(speed) and speed > 0):
                raise LaunchError(f"--speed must be a positive number or 'max', got {self.speed!r}")
        if self.seed is not None and not 0 <= self.seed <= _MAX_SEED:
            raise LaunchError(f"--seed must be 0-{_MAX_SEED}, got {self.seed}")
        known = world_options()
        for name, value in self.world_options.items():
            option = known.get(name)
            if option is None:
                raise LaunchError(f"--{name}: no world has this option; theirs are {', '.join(known)}")
            low, high = option.minimum, option.maximum
            if (low is not None and value < low) or (high is not None and value > high):
                raise LaunchError(f"{option.flag} must be {low:g}-{high:g}, got {value}")

    def with_seed(self) -> LaunchOptions:
        """These options with a seed drawn at random if none was given, so a run can be repeated."""
        if self.seed is not None:
            return self
        return dataclasses.replace(self, seed=random.SystemRandom().randrange(_MAX_SEED + 1))

    def endpoint_ports(self, environ: Mapping[str, str]) -> dict[str, int]:
        """The ports the core's protocol endpoints will listen on (those that are on), by the
        flag that sets each: the option, else the core's ``SKYDECK_*`` setting in ``environ``."""
        ports = {}
        for flag, setting in _ENDPOINTS:
            port = getattr(self, setting)
            if port is None:
                text = environ.get(CoreSettings.model_config["env_prefix"] + setting.upper(), "")
                port = int(text) if text.isdigit() else CoreSettings.model_fields[setting].default
            if port:
                ports[flag] = port
        return ports

    def placeholders(self) -> dict[str, str]:
        """The values of ``{speed}``, each world option's (``{boxes}``, ``{robots}``...),
        ``{base_port}`` and (once set) ``{seed}``."""
        values = {
            "speed": self.speed,
            **{name: str(self.world_options.get(name, option.default)) for name, option in world_options().items()},
            "base_port": str(self.base_port),
        }
        if self.seed is not None:
            values["seed"] = str(self.seed)
        return values


@dataclass(frozen=True)
class NodePlan:
    """One process to start: its port, filled-in arguments and extra environment."""

    name: str
    run: str
    port: int
    args: tuple[str, ...] = ()
    env: dict[str, str] = field(default_factory=dict)
    respawn: bool = True
    ready_timeout_s: float = 20.0
    is_core: bool = False

    @property
    def url(self) -> str:
        """Where the node serves, e.g. ``http://127.0.0.1:8001``."""
        return f"http://127.0.0.1:{self.port}"


def plan_launch(spec: LaunchSpec, options: LaunchOptions) -> tuple[NodePlan, ...]:
    """The processes to start, in start order: the core first, then the rest as listed.

    Raises ``LaunchError`` for an ``exclude`` name the launch file does not have, a port past
    65535, ``{seed}`` in the file with no seed in the options (see ``with_seed``), or a world's
    option (``--boxes``) given to a launch file that has no use for it.
    """
    for name, value in options.world_options.items():
        if not spec.uses(name):
            option = world_options()[name]
            launch_file = WORLDS[option.world].launch_file
            command = "skydeck launch" if WORLDS[option.world] is default_world() else f"skydeck launch {launch_file}"
            raise LaunchError(
                f"{option.flag} {value}: this launch file does not use it (no {{{name}}} in its "
                f"nodes); {option.flag} is the {option.world} world's (`{command}`)"
            )
    unknown = [name for name in options.exclude if name not in spec.names]
    if unknown:
        raise LaunchError(
            f"--exclude names {', '.join(repr(name) for name in unknown)}, which the launch file "
            f"does not have; its nodes are: {', '.join(spec.names)}"
        )
    last = options.base_port + max(node.port_offset for node in spec.nodes)
    if last > 65535:
        raise LaunchError(
            f"--base-port {options.base_port} puts the last node on port {last}, past 65535: "
            "choose a lower base port"
        )
    values = options.placeholders()
    nodes = [node for node in spec.nodes if node.name not in options.exclude]
    nodes.sort(key=lambda node: not node.is_core)  # stable: the core first, the rest as listed
    plans = [_plan(node, options.base_port, values) for node in nodes]
    # The core's endpoint ports, when given, are its flags, as `skydeck core` takes them.
    endpoints = tuple(
        word
        for flag, setting in _ENDPOINTS
        if getattr(options, setting) is not None
        for word in (flag, str(getattr(options, setting)))
    )
    return tuple(
        dataclasses.replace(plan, args=(*plan.args, *endpoints)) if plan.is_core and endpoints else plan for plan in plans
    )


def core_url(spec: LaunchSpec, options: LaunchOptions) -> str:
    """The URL every child is given as ``SKYDECK_CORE_URL``: the core's port in this launch."""
    offset = next((node.port_offset for node in spec.nodes if node.is_core), 0)
    return f"http://127.0.0.1:{options.base_port + offset}"


def default_command(plan: NodePlan) -> list[str]:
    """``skydeck core --port P`` for the core, else ``skydeck run RUN --port P ARGS...``."""
    cli = [sys.executable, "-m", "services.cli"]
    if plan.is_core:
        return [*cli, "core", "--port", str(plan.port), *plan.args]
    return [*cli, "run", plan.run, "--port", str(plan.port), *plan.args]


def _plan(node: NodeSpec, base_port: int, values: dict[str, str]) -> NodePlan:
    try:
        args = tuple(arg.format_map(values) for arg in node.args)
        env = {key: text.format_map(values) for key, text in node.env.items()}
    except KeyError as missing:
        raise LaunchError(
            f"node {node.name!r} uses {{{missing.args[0]}}} but the options give it no value"
        ) from None
    return NodePlan(
        name=node.name,
        run=node.run,
        port=base_port + node.port_offset,
        args=args,
        env=env,
        respawn=node.respawn,
        ready_timeout_s=node.ready_timeout_s,
        is_core=node.is_core,
    )
