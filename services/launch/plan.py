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
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from services.launch.errors import LaunchError
from services.launch.spec import LaunchSpec, NodeSpec
from services.protocols.endpoints import DEFAULT_BASE_PORT, ENDPOINTS, Endpoint
from services.runtime.ports import port_is_free
from sim_server.worlds import WORLDS, default_world, world_options  # the table only: no PyBullet

__all__ = [
    "DEFAULT_BASE_PORT",
    "LaunchOptions",
    "NodePlan",
    "check_ports_free",
    "core_url",
    "default_command",
    "plan_launch",
]

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
    # The core's protocol endpoints' ports that were given (a flag, or SKYDECK_<NAME>_PORT:
    # with_given_ports), by endpoint name; 0 turns one off. Every other endpoint listens on its
    # default port moved as far as the base port moves the core (rosbridge 9090 at base 8000,
    # 20430 at base 19340), so launches side by side do not compete for them.
    endpoint_ports: Mapping[str, int] = field(default_factory=dict)
    # `--ros2`: the ROS 2 bridge (`skydeck run ros2_bridge`) starts with the rest, on the port
    # after the launch file's last, on ROS_DOMAIN_ID's domain (else 0).
    ros2: bool = False

    def __post_init__(self) -> None:
        if not 1 <= self.base_port <= 65535:
            raise LaunchError(f"--base-port must be a port number 1-65535, got {self.base_port}")
        names = {endpoint.name for endpoint in ENDPOINTS}
        for name, port in self.endpoint_ports.items():
            if name not in names:
                raise LaunchError(f"no protocol endpoint {name!r}; the endpoints are {', '.join(sorted(names))}")
            if not 0 <= port <= 65535:
                raise LaunchError(f"--{name}-port must be a port number 0-65535 (0: off), got {port}")
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

    def with_given_ports(self, given: Mapping[str, int]) -> LaunchOptions:
        """These options, with endpoint ports ``given`` elsewhere (``SKYDECK_*_PORT``) where
        these give none."""
        return dataclasses.replace(self, endpoint_ports={**given, **self.endpoint_ports})

    def core_endpoints(self) -> dict[Endpoint, int]:
        """The port of every protocol endpoint of the core (0: off): as given, else moved with
        the base port (:meth:`~services.protocols.endpoints.Endpoint.port_at`)."""
        return {e: self.endpoint_ports.get(e.name, e.port_at(self.base_port)) for e in ENDPOINTS}

    def endpoints_notice(self) -> str:
        """One line naming the core's endpoint ports, and whether they moved with the base port
        (``protocol endpoints rosbridge :20430, foxglove :20105 (moved with --base-port)``)."""
        ports = self.core_endpoints()
        moved = any(e.name not in self.endpoint_ports and port != e.default_port for e, port in ports.items())
        named = ", ".join(f"{e.name} :{port}" for e, port in ports.items() if port)
        return f"protocol endpoints {named}" + (" (moved with --base-port)" if moved else "") if named else ""

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
    package: str | None = None  # run is this workspace package's executable
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
    65535 (a node's, or a protocol endpoint's moved with the base port), ``{seed}`` in the file
    with no seed in the options (see ``with_seed``), or a world's option (``--boxes``) given to a
    launch file that has no use for it.
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
    if last + options.ros2 > 65535:
        raise LaunchError(
            f"--base-port {options.base_port} puts the last node on port {last}, past 65535: "
            "choose a lower base port"
        )
    values = options.placeholders()
    nodes = [node for node in spec.nodes if node.name not in options.exclude]
    nodes.sort(key=lambda node: not node.is_core)  # stable: the core first, the rest as listed
    plans = [_plan(node, options.base_port, values) for node in nodes]
    if options.ros2:
        plans.append(NodePlan(name="ros2_bridge", run="ros2_bridge", port=last + 1))
    if not any(plan.is_core for plan in plans):
        return tuple(plans)
    for endpoint, port in options.core_endpoints().items():
        if port > 65535:
            raise LaunchError(
                f"--base-port {options.base_port} moves the {endpoint.name} endpoint to port {port}, past "
                f"65535: choose a lower base port, or give {endpoint.flag} PORT (0: off)"
            )
    # The core's endpoint ports, given or moved, are its flags, as `skydeck core` takes them.
    endpoints = tuple(
        word
        for e, port in options.core_endpoints().items()
        if e.name in options.endpoint_ports or port != e.default_port
        for word in (e.flag, str(port))
    )
    return tuple(dataclasses.replace(plan, args=(*plan.args, *endpoints)) if plan.is_core else plan for plan in plans)


def core_url(spec: LaunchSpec, options: LaunchOptions) -> str:
    """The URL every child is given as ``SKYDECK_CORE_URL``: the core's port in this launch."""
    offset = next((node.port_offset for node in spec.nodes if node.is_core), 0)
    return f"http://127.0.0.1:{options.base_port + offset}"


def default_command(plan: NodePlan) -> list[str]:
    """``skydeck core --port P`` for the core, else ``skydeck run RUN --port P ARGS...`` (``skydeck
    run PACKAGE RUN ...`` for a package's executable)."""
    cli = [sys.executable, "-m", "services.cli"]
    if plan.is_core:
        return [*cli, "core", "--port", str(plan.port), *plan.args]
    program = [plan.package, plan.run] if plan.package else [plan.run]
    return [*cli, "run", *program, "--port", str(plan.port), *plan.args]


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
        package=node.package,
        args=args,
        env=env,
        respawn=node.respawn,
        ready_timeout_s=node.ready_timeout_s,
        is_core=node.is_core,
    )


def check_ports_free(plans: Sequence[NodePlan], options: LaunchOptions) -> None:
    """LaunchError naming the first port of the launch (a node's, the core's endpoints') in use."""
    for plan in plans:
        if not port_is_free(plan.port):
            raise LaunchError(
                f"port {plan.port} for {plan.name} is already in use: is another launch or "
                "node running? stop it or choose another --base-port",
                node=plan.name,
            )
    if not any(plan.is_core for plan in plans):
        return
    for endpoint, port in options.core_endpoints().items():
        if port and not port_is_free(port):
            raise LaunchError(
                f"port {port} for the core's {endpoint.name} endpoint is already in use (another Skydeck "
                f"or {endpoint.name} server?): choose another with {endpoint.flag} PORT, or "
                f"{endpoint.flag} 0 to turn it off"
            )
