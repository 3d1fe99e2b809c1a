"""``skydeck run sim``: the simulator node, in the world the table names (:mod:`sim_server.worlds`).

    skydeck run sim --seed 1 --boxes 8 --speed max        # the drone world (the default)
    skydeck run sim --world robot --robots 2              # the robot world

Every world takes ``--seed``, ``--speed`` and the camera's flags; each adds its own options (its
settings class's fields), and refuses another world's (``--robots`` is the robot world's).
"""

from __future__ import annotations

import argparse
from typing import Any, NoReturn

from pydantic import ValidationError

from services.runtime import spin
from sim_server.settings import (
    MAX_CAMERA_HEIGHT,
    MAX_CAMERA_RATE_HZ,
    MAX_CAMERA_WIDTH,
    MIN_CAMERA_RATE_HZ,
    MIN_CAMERA_SIDE,
    SimSettings,
)
from sim_server.worlds import (
    WORLDS,
    UnknownWorld,
    WorldEntry,
    default_world,
    find_world,
    world_options,
)

__all__ = ["main", "world_settings"]


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="skydeck run sim",
        description=f"The PyBullet simulator, in one of its worlds: {', '.join(WORLDS)}.",
    )
    worlds = "; ".join(f"{entry.name}: {entry.summary}" for entry in WORLDS.values())
    parser.add_argument("--world", help=f"{worlds} (default {default_world().name})")
    parser.add_argument("--seed", help="random seed; the same seed gives the same world")
    parser.add_argument("--speed", help="times real time, or 'max' (default 1)")
    for option in world_options().values():
        parser.add_argument(option.flag, help=f"{option.world} world: {option.description}")
    parser.add_argument("--camera-width", help=f"camera image width, {MIN_CAMERA_SIDE}-{MAX_CAMERA_WIDTH} pixels (default 320)")
    parser.add_argument("--camera-height", help=f"camera image height, {MIN_CAMERA_SIDE}-{MAX_CAMERA_HEIGHT} pixels (default 240)")
    parser.add_argument(
        "--camera-rate",
        help=f"camera frames a second while watched, {MIN_CAMERA_RATE_HZ:g}-{MAX_CAMERA_RATE_HZ:g} (default 5)",
    )
    return parser


def world_settings(argv: list[str] | None = None) -> tuple[WorldEntry, SimSettings]:
    """The world the flags (and ``SKYDECK_SIM_*``) name, and its settings; a bad flag exits with
    the parser's one-line error naming it."""
    parser = _parser()
    flags = {key: value for key, value in vars(parser.parse_args(argv)).items() if value is not None}
    common = _validated(parser, SimSettings, flags)
    try:
        entry = find_world(common.world)
    except UnknownWorld as error:
        parser.error(f"--world: {error}")
    settings_type = entry.settings_type()
    for other in WORLDS.values():
        foreign = [
            name for name in other.settings_type().options_given(flags) if name not in settings_type.model_fields
        ]
        if foreign:
            _refuse_foreign(parser, entry, other, foreign[0], settings_type.own_options())
    return entry, _validated(parser, settings_type, flags)


def _refuse_foreign(
    parser: argparse.ArgumentParser, entry: WorldEntry, owner: WorldEntry, name: str, own: list[str]
) -> NoReturn:
    flag = "--" + name.replace("_", "-")
    takes = ", ".join("--" + option.replace("_", "-") for option in own) or "none of its own"
    parser.error(
        f"{flag} (SKYDECK_SIM_{name.upper()}) is the {owner.name} world's (--world {owner.name}); "
        f"the {entry.name} world's options: {takes}"
    )


def _validated(parser: argparse.ArgumentParser, settings_type: type[Any], flags: dict[str, Any]) -> Any:
    try:
        return settings_type(**{key: value for key, value in flags.items() if key in settings_type.model_fields})
    except ValidationError as error:
        first = error.errors()[0]
        flag = str(first["loc"][0]).replace("_", "-")
        parser.error(f"--{flag}: {first['msg']}")


def main(argv: list[str] | None = None) -> int:
    """``skydeck run sim [--world NAME] [--seed N] [--speed F|max] [the world's options]
    [--camera-width W] [--camera-height H] [--camera-rate HZ]``."""
    entry, settings = world_settings(argv)
    spin(entry.node_type()(settings))
    return 0
