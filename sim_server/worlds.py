"""The table of worlds: one row per world, read by the simulator's entry (``skydeck run sim
--world NAME``), the core's ``GET /api/config``, the CLI and the launcher.

    drone   the workshop's drone and falling boxes     skydeck launch           (workshop.yaml)
    robot   Neato robots in a room, a walking person   skydeck launch robot     (robot.yaml)
    soccer  the robot world, a ball, robots' cameras   skydeck launch soccer    (soccer.yaml)

A row names its world's parts by import path, loaded only when asked for: reading the table
loads no world, and the core and the launcher never load PyBullet. A new world is one package
(its node, settings and description, on the floor of :mod:`sim_server.world_node`,
:mod:`sim_server.settings` and :mod:`sim_server.description`) and one row here; a world built
on another (the soccer room on the robot world) imports that world's package too, and says so
in its description (``extends``).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

from shared_models.errors import SkydeckError

if TYPE_CHECKING:
    from sim_server.description import WorldDescription
    from sim_server.settings import SimSettings
    from sim_server.world_node import WorldNode

__all__ = [
    "WORLDS",
    "UnknownWorld",
    "WorldEntry",
    "WorldOption",
    "default_world",
    "find_world",
    "world_options",
    "worlds_config",
]


class UnknownWorld(SkydeckError, LookupError):
    """A world name the table does not have."""

    def __init__(self, name: str) -> None:
        self.name = name
        super().__init__(f"no world {name!r}: the worlds are {', '.join(WORLDS)}")


@dataclass(frozen=True, slots=True)
class WorldEntry:
    """One world: its name, what it is, and where its parts are (``module:attribute``)."""

    name: str
    summary: str
    """One line, for ``skydeck run sim --help``."""
    node: str
    """Its node class, a :class:`~sim_server.world_node.WorldNode` taking ``(settings, node settings)``."""
    settings: str
    """Its settings class, a :class:`~sim_server.settings.SimSettings` with the world's own options."""
    description: str
    """Its :class:`~sim_server.description.WorldDescription`."""
    launch_file: str
    """The shipped launch file (``services/launch/NAME.yaml``) that starts the world's system."""

    def node_type(self) -> Callable[[Any], WorldNode[Any]]:
        """The node class, called with the world's settings (loads the world: PyBullet and all)."""
        return cast("Callable[[Any], WorldNode[Any]]", _load(self.node))

    def settings_type(self) -> type[SimSettings]:
        """The settings class (pure: no PyBullet)."""
        return cast("type[SimSettings]", _load(self.settings))

    def describe(self) -> WorldDescription:
        """The world's description (pure: no PyBullet)."""
        return cast("WorldDescription", _load(self.description))


@dataclass(frozen=True, slots=True)
class WorldOption:
    """A world's own option (``boxes``), as ``skydeck run sim`` and ``skydeck launch`` take it."""

    name: str
    world: str
    """The world whose option it is."""
    default: Any
    minimum: float | None
    maximum: float | None
    description: str

    @property
    def flag(self) -> str:
        """``--boxes``."""
        return "--" + self.name.replace("_", "-")


def _load(path: str) -> object:
    module, _, attribute = path.partition(":")
    return getattr(importlib.import_module(module), attribute)


WORLDS: dict[str, WorldEntry] = {
    entry.name: entry
    for entry in (
        WorldEntry(
            name="drone",
            summary="the workshop's drone and falling boxes",
            node="sim_server.drone.node:DroneSimNode",
            settings="sim_server.drone.settings:DroneSettings",
            description="sim_server.drone.description:DESCRIPTION",
            launch_file="workshop",
        ),
        WorldEntry(
            name="robot",
            summary="Neato robots in a room with box obstacles and a walking person",
            node="sim_server.robot.node:RobotSimNode",
            settings="sim_server.robot.settings:RobotSettings",
            description="sim_server.robot.description:DESCRIPTION",
            launch_file="robot",
        ),
        WorldEntry(
            name="soccer",
            summary="the robot world with a ball to push and a camera on every robot",
            node="sim_server.soccer.node:SoccerSimNode",
            settings="sim_server.soccer.settings:SoccerSettings",
            description="sim_server.soccer.description:DESCRIPTION",
            launch_file="soccer",
        ),
    )
}
"""Every world, by name; the first is the default."""


def default_world() -> WorldEntry:
    """The world ``skydeck run sim`` builds when none is named: the table's first."""
    return next(iter(WORLDS.values()))


def find_world(name: str | None) -> WorldEntry:
    """The row of world ``name`` (the default world for ``None``); :class:`UnknownWorld` if the
    table has none."""
    if name is None:
        return default_world()
    try:
        return WORLDS[name]
    except KeyError:
        raise UnknownWorld(name) from None


def worlds_config() -> dict[str, dict[str, Any]]:
    """Each world's part of ``GET /api/config``, by name."""
    return {name: entry.describe().config() for name, entry in WORLDS.items()}


def world_options() -> dict[str, WorldOption]:
    """Every world's own options, by name (their settings classes' fields beyond every world's).
    An option a world shares with the world it extends (the soccer room's ``--robots``) is the
    first world's, which declared it."""
    options: dict[str, WorldOption] = {}
    for entry in WORLDS.values():
        settings = entry.settings_type()
        for name in settings.own_options():
            field = settings.model_fields[name]
            low, high = settings.option_range(name)
            options.setdefault(name, WorldOption(name, entry.name, field.default, low, high, field.description or name))
    return options
