"""``skydeck class ROSTER``: a class on one machine (docs/class.md)."""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "class",
        help="run a class: one core fenced by the students' tokens, a robot per student under /NAME",
        description=(
            "Starts the core and the robot world with a robot per student of ROSTER (a CSV of names, "
            "one a line, or YAML with `students:` and `world:`), each student fenced to /NAME. The "
            "tokens are written once to --tokens (0600): hand each student their line. See docs/class.md."
        ),
    )
    p.add_argument("roster", type=Path, help="the students: CSV (one name a line) or YAML (students:, world:)")
    p.add_argument("--tokens", type=Path, default=Path("class-tokens.csv"), metavar="FILE",
                   help="where the tokens are written once, `name,token` lines (default class-tokens.csv); "
                        "read back when the class starts again")  # fmt: skip
    p.add_argument("--host", default="127.0.0.1", help="where the class listens: 127.0.0.1 (default) or 0.0.0.0 (every interface)")
    p.add_argument("--advertise", metavar="ADDRESS", help="the address students reach this machine at (with --host 0.0.0.0)")
    p.add_argument("--rules", type=Path, metavar="FILE", help="the class's rules: what students share and read (YAML; docs/security.md)")
    p.add_argument("--gradebook", type=Path, metavar="FILE",
                   help="the gradebook the class page shows (`skydeck grade ... --class` writes OUT/gradebook.json)")  # fmt: skip
    p.add_argument("--base-port", type=int, default=8000, help="the core's port; the world's is the next (default 8000)")
    p.add_argument("--speed", default="1", help="simulator speed: times real time, or 'max' (default 1)")
    p.add_argument("--seed", type=int, help="world seed (default: a random one, printed)")
    p.add_argument("--obstacles", type=int, default=0, help="box obstacles in the room (default 0)")
    p.set_defaults(func=_class)


def _class(args: argparse.Namespace) -> int:
    from services.classroom import ClassOptions, read_roster, run_class

    roster = read_roster(args.roster)  # a ClassroomError is one line, by main
    options = ClassOptions(
        tokens=args.tokens, host=args.host, advertise=args.advertise, rules=args.rules, gradebook=args.gradebook,
        base_port=args.base_port, speed=args.speed, seed=args.seed, obstacles=args.obstacles,
    )  # fmt: skip
    return run_class(roster, options)
