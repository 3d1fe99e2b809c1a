"""``skydeck core`` (roscore) and ``skydeck run NODE`` (rosrun): start one process."""

from __future__ import annotations

import argparse
import importlib
import os
import runpy
import sys
from pathlib import Path

from services.cli.errors import CliError

__all__ = ["BUILTIN_NODES", "add_parsers"]

# Built-in nodes by the name `skydeck run` and launch files use; each module has main(argv).
BUILTIN_NODES = {
    "sim": "sim_server.node",
    "perception": "services.perception.node",
    "control": "services.control.node",
    "ai": "services.ai.node",
}


def add_parsers(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    core = subparsers.add_parser("core", help="run the core: registry, gateway, dashboard (like roscore)")
    _add_server_flags(core, default_port=8000)
    core.set_defaults(func=_core)

    run = subparsers.add_parser(
        "run",
        help="run one node: a built-in (sim, perception, control, ai) or a .py file (like rosrun)",
        description="Flags after NODE that `run` does not know are passed to the node (e.g. sim's --seed).",
    )
    run.add_argument("node", help="sim | perception | control | ai | path/to/node.py")
    _add_server_flags(run, default_port=None)
    run.add_argument("--core-url", help="where the core is (default: SKYDECK_CORE_URL or http://127.0.0.1:8000)")
    run.add_argument("--use-sim-time", action="store_true", help="follow /clock instead of the wall clock")
    run.set_defaults(func=_run)


def _add_server_flags(parser: argparse.ArgumentParser, *, default_port: int | None) -> None:
    parser.add_argument("--host", help="address to listen on (default 127.0.0.1; 0.0.0.0 in containers)")
    parser.add_argument("--port", type=_port, default=default_port, help="port to listen on")
    parser.add_argument("--advertise-url", help="URL other processes reach this one at (containers)")
    parser.add_argument("--log-level", choices=["debug", "info", "warning", "error"], help="default info")


def _port(text: str) -> int:
    if not text.isdigit() or not 0 <= int(text) <= 65535:
        raise argparse.ArgumentTypeError(f"expected a port number 0-65535, got {text!r}")
    return int(text)


def _export_settings(args: argparse.Namespace) -> None:
    """Flags become SKYDECK_* variables, which the node's and core's settings read."""
    for flag, variable in (
        ("host", "SKYDECK_HOST"),
        ("port", "SKYDECK_PORT"),
        ("advertise_url", "SKYDECK_ADVERTISE_URL"),
        ("core_url", "SKYDECK_CORE_URL"),
        ("log_level", "SKYDECK_LOG_LEVEL"),
    ):
        value = getattr(args, flag, None)
        if value is not None:
            os.environ[variable] = str(value)
    if getattr(args, "use_sim_time", False):
        os.environ["SKYDECK_USE_SIM_TIME"] = "true"


def _core(args: argparse.Namespace) -> int:
    if args.extra:
        raise CliError(f"unknown option for `skydeck core`: {' '.join(args.extra)}")
    _export_settings(args)
    from services.core.server import serve

    serve()
    return 0


def _run(args: argparse.Namespace) -> int:
    _export_settings(args)
    node_argv = list(args.extra)
    if args.node in BUILTIN_NODES:
        module = importlib.import_module(BUILTIN_NODES[args.node])
        return int(module.main(node_argv) or 0)
    path = Path(args.node)
    if path.suffix != ".py":
        raise CliError(
            f"unknown node {args.node!r}: a built-in ({', '.join(BUILTIN_NODES)}) or a path to a .py file"
        )
    if not path.is_file():
        raise CliError(f"no such node file: {path}")
    sys.argv = [str(path), *node_argv]
    sys.path.insert(0, str(path.resolve().parent))
    runpy.run_path(str(path), run_name="__main__")
    return 0
