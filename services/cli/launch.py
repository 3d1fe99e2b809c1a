"""``skydeck launch [FILE]`` (roslaunch): the core, the simulator and the nodes of a launch file."""

from __future__ import annotations

import argparse
import asyncio
import random

from services.cli.errors import CliError

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "launch",
        help="start the core, the simulator and the nodes of a launch file (default: the workshop)",
    )
    p.add_argument("file", nargs="?", help="a YAML launch file (default: the workshop system)")
    p.add_argument("--base-port", type=int, default=8000, help="core on N, sim N+1, perception N+2, ... (default 8000)")
    p.add_argument("--speed", default="1", help="simulator speed: times real time, or 'max' (default 1)")
    p.add_argument("--seed", type=int, help="world seed (default: a random one, printed)")
    p.add_argument("--boxes", type=int, default=8, help="number of boxes (default 8)")
    p.add_argument("--exclude", default="", help="nodes to leave out, comma-separated (e.g. ai)")
    p.set_defaults(func=_launch)


def _launch(args: argparse.Namespace) -> int:
    if not 1 <= args.base_port <= 65535 - 10:
        raise CliError(f"--base-port must be between 1 and {65535 - 10}, got {args.base_port}")
    from services.launch import (
        LaunchError,
        LaunchFileError,
        LaunchOptions,
        Supervisor,
        default_launch_file,
        load_launch_file,
    )

    try:
        spec = load_launch_file(args.file or default_launch_file())
    except LaunchFileError as error:
        raise CliError(str(error)) from None
    seed = args.seed if args.seed is not None else random.randrange(2**31)
    options = LaunchOptions(
        base_port=args.base_port,
        speed=args.speed,
        seed=seed,
        boxes=args.boxes,
        exclude=tuple(name for name in args.exclude.split(",") if name),
    )
    print(f"[launch] world seed {seed} (repeat it with --seed {seed})", flush=True)
    try:
        return asyncio.run(Supervisor(spec, options).run())
    except LaunchError as error:
        raise CliError(str(error)) from None
