"""``skydeck``: the entry point; errors are one line and a non-zero exit, never a traceback."""

from __future__ import annotations

import argparse
import os
import sys
from typing import cast

from pydantic import ValidationError

from services.cli import (
    action,
    bag,
    bridge,
    completion,
    doctor,
    grade,
    interface,
    node,
    param,
    run,
    service,
    topic,
)
from services.cli.settings import CliSettings, use_cli_settings
from services.cli.suggestions import SuggestingParser
from shared_models.errors import SkydeckError

__all__ = ["build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    """The whole command line, one subparser per verb group."""
    parser = SuggestingParser(
        prog="skydeck",
        description="ROS-style robot software over HTTP and WebSocket. The core is found at SKYDECK_CORE_URL.",
    )
    # The verbs that need the whole command line (completion's) find it here.
    parser.set_defaults(parser=parser)
    # Every level is a SuggestingParser (argparse makes subparsers of the parser's class); the
    # verb modules take the base type, which the action's type parameter cannot say (invariant).
    subparsers = cast(
        "argparse._SubParsersAction[argparse.ArgumentParser]",
        parser.add_subparsers(dest="command", required=True, metavar="COMMAND"),
    )
    run.add_parsers(subparsers)
    for module in (topic, service, action, node, param, interface, bag, bridge, grade, doctor, completion):
        module.add_parser(subparsers)
    _add_optional(subparsers)
    return parser


def _add_optional(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    # Verbs whose modules pull in heavier dependencies (launch), or run what an installation may
    # not have (bench: the checkout's benchmarks), register themselves here.
    from services.cli import bench, classroom, launch

    launch.add_parser(subparsers)
    classroom.add_parser(subparsers)
    bench.add_parser(subparsers)


def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit status."""
    parser = build_parser()
    args, extra = parser.parse_known_args(argv)
    rest = getattr(args, "extra_positionals", None)
    if rest is not None:  # argparse leaves positionals that follow options (`launch F --speed 2 a:=1`)
        getattr(args, rest).extend(word for word in extra if not word.startswith("-"))
        extra = [word for word in extra if word.startswith("-")]
    if extra and args.command != "run" and args.command != "core":
        parser.error(f"unrecognized arguments: {' '.join(extra)}")
    args.extra = extra
    try:
        use_cli_settings(CliSettings())  # read once, here: every verb asks cli_settings()
        return int(args.func(args) or 0)
    except KeyboardInterrupt:  # first: rospy's ROSInterruptException is also a Skydeck error
        return 130
    except SkydeckError as error:  # every error Skydeck raises on purpose says what to do
        print(f"skydeck: error: {error}", file=sys.stderr)
        return 1
    except ValidationError as error:  # a SKYDECK_* variable that does not fit its setting
        first = error.errors(include_url=False)[0]
        setting = "SKYDECK_" + "_".join(str(part) for part in first["loc"]).upper()
        print(f"skydeck: error: {setting}: {first['msg']}", file=sys.stderr)
        return 1
    except BrokenPipeError:
        # Whoever read our output stopped (`skydeck topic echo /x | head`): as a shell tool does,
        # stop quietly; point stdout at nothing so the interpreter's final flush cannot fail.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
