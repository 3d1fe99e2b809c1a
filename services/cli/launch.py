"""``skydeck launch [FILE]`` (roslaunch): the core, the simulator and the nodes of a launch file."""

from __future__ import annotations

import argparse
import re
from collections.abc import Mapping
from pathlib import Path

from services.cli.errors import CliError
from services.cli.run import add_endpoint_flags
from sim_server.worlds import WORLDS, default_world, world_options  # the table only: no PyBullet

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "launch",
        help="start the core, the simulator and the nodes of a launch file (default: the workshop)",
    )
    p.add_argument(
        "file",
        nargs="?",
        help="a YAML launch file, a roslaunch XML file (.launch), a ROS 2 launch file (.launch.py, "
        "ROS 2 XML or YAML; `skydeck launch PACKAGE FILE` finds it in a workspace package, as ros2 launch), "
        "or a shipped one by name: "
        + ", ".join(f"{entry.launch_file} (the {name} world)" for name, entry in WORLDS.items())
        + f"; default {default_world().launch_file}",
    )
    p.add_argument(
        "launch_args",
        nargs="*",
        metavar="NAME:=VALUE",
        help="the launch file's arguments (a YAML file's `arguments:`, a roslaunch file's <arg>s, "
        "a ROS 2 file's DeclareLaunchArgument)",
    )
    p.add_argument(
        "--show-args", action="store_true", help="list the arguments the launch file takes, with defaults, and exit"
    )
    p.add_argument(
        "--base-port",
        type=int,
        help="core on N, sim N+1, perception N+2, ... (default: the port of a local SKYDECK_CORE_URL, else 8000)",
    )
    p.add_argument("--speed", default="1", help="simulator speed: times real time, or 'max' (default 1)")
    p.add_argument("--seed", type=int, help="world seed (default: a random one, printed)")
    for option in world_options().values():  # each world's own (--boxes, --robots...)
        p.add_argument(option.flag, type=int, dest=f"world_{option.name}", help=f"{option.world} world: {option.description}")
    p.add_argument("--exclude", default="", help="nodes to leave out, comma-separated (e.g. perception,ai)")
    p.add_argument("--ros2", action="store_true", help="start the ROS 2 bridge too (`skydeck bridge ros2`; domain ROS_DOMAIN_ID, else 0)")
    add_endpoint_flags(p, moved_by=", moved as far as the base port")
    p.set_defaults(func=_launch, extra_positionals="launch_args")  # NAME:=VALUE after options too


def _launch(args: argparse.Namespace) -> int:
    # Imported here: the supervisor is only needed by this verb.
    from services.launch import (
        DEFAULT_BASE_PORT,
        LaunchOptions,
        launch_arguments,
        package_launch_file,
        run_launch,
        shipped_launch_files,
        show_arguments,
    )
    from services.launch.settings import LaunchSettings
    from services.protocols.endpoints import ENDPOINTS

    if args.file is not None and ":=" in args.file:  # `skydeck launch name:=value`: the default file's
        args.launch_args.insert(0, args.file)
        args.file = None
    if args.file is not None and _names_a_package(args.file, args.launch_args, shipped_launch_files()):
        # `skydeck launch PACKAGE FILE` (ros2 launch): the file in the workspace package
        args.file = str(package_launch_file(args.file, args.launch_args.pop(0)))
    if args.show_args:
        print(show_arguments(launch_arguments(args.file)))
        return 0

    options = LaunchOptions(
        base_port=DEFAULT_BASE_PORT if args.base_port is None else args.base_port,
        speed=args.speed,
        seed=args.seed,
        exclude=tuple(name.strip() for name in args.exclude.split(",") if name.strip()),
        world_options={
            name: value for name in world_options() if (value := getattr(args, f"world_{name}")) is not None
        },
        ros2=args.ros2,
        endpoint_ports={e.name: getattr(args, e.setting) for e in ENDPOINTS if getattr(args, e.setting) is not None},
    )
    if args.ros2:  # said at once, before anything starts
        from services.protocols.ros2.extra import missing_extra

        if (reason := missing_extra()) is not None:
            raise CliError(reason)
    launch_args = {}
    for text in args.launch_args:
        name, separator, value = text.partition(":=")
        if not separator or not name:
            raise CliError(f"{text!r}: launch arguments are NAME:=VALUE (e.g. use_sim_time:=false)")
        launch_args[name] = value
    settings = LaunchSettings()  # the launcher's environment, read once
    # a LaunchError is one line, by main
    return run_launch(args.file, options, launch_args=launch_args, settings=settings, base_port_given=args.base_port is not None)


def _names_a_package(file: str, launch_args: list[str], shipped: Mapping[str, object]) -> bool:
    """Whether ``skydeck launch FILE WORD`` is ``ros2 launch``'s ``PACKAGE FILE``: a bare name
    that is no file here and no shipped launch, then a word that is no ``name:=value``."""
    return (
        bool(launch_args)
        and ":=" not in launch_args[0]
        and re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", file) is not None
        and file not in shipped
        and not Path(file).exists()
    )
