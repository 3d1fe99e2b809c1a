"""Argument types shared by the CLI's verbs: ROS names and positive numbers, checked at parse time."""

from __future__ import annotations

import argparse
import math
import os
from collections.abc import Callable
from pathlib import Path

from services.cli.errors import CliError

__all__ = [
    "add_noun",
    "add_verb",
    "known_type_of",
    "known_type",
    "node_name",
    "positive_float",
    "positive_int",
    "ros_name",
    "use_current_workspace",
    "writable_file",
]


def add_noun(
    subparsers: argparse._SubParsersAction[argparse.ArgumentParser], name: str, help: str
) -> argparse._SubParsersAction[argparse.ArgumentParser]:
    """The command ``name`` (``topic``, ``bag``, ...) whose verbs the caller adds to what it returns."""
    return subparsers.add_parser(name, help=help).add_subparsers(dest="verb", required=True, metavar="VERB")


def add_verb(
    verbs: argparse._SubParsersAction[argparse.ArgumentParser], name: str, run: Callable[[argparse.Namespace], int],
    help: str, *positionals: str,
) -> argparse.ArgumentParser:
    """The verb ``name`` running ``run(args)``, with its plain positional arguments; the caller adds
    its options (and any positional with a help of its own) to what it returns."""
    verb = verbs.add_parser(name, help=help)
    for positional in positionals:
        verb.add_argument(positional)
    verb.set_defaults(func=run)
    return verb


def positive_int(text: str) -> int:
    """argparse type: an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return value


def positive_float(text: str) -> float:
    """argparse type: a finite number > 0."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (value > 0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"expected a positive number, got {text!r}")
    return value


def writable_file(text: str) -> Path:
    """argparse type: a file path that can be written (missing folders will be made), checked
    before any work is done: a benchmark's results must not be lost at the end of the run."""
    path = Path(text).expanduser()
    existing = next(folder for folder in path.absolute().parents if folder.exists())
    if path.is_dir():
        problem = "it is a folder"
    elif not existing.is_dir():
        problem = f"{existing} is not a folder"
    elif not os.access(existing, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        problem = "permission denied"
    else:
        return path
    raise argparse.ArgumentTypeError(f"cannot write {text}: {problem}")


def node_name(text: str) -> str:
    """A node's full name as the user typed it, resolved ("sim" -> "/sim"); a node in a
    namespace (``-r __ns:=/robot1``) is named with it: ``/robot1/estop``."""
    from shared_models import InvalidNameError, resolve_name, resolve_node_name

    try:
        return resolve_name(text) if "/" in text.strip("/") else resolve_node_name(text)
    except InvalidNameError as error:
        raise CliError(str(error)) from None


def ros_name(text: str) -> str:
    """A topic or service name as the user typed it, resolved ("my_point" -> "/my_point")."""
    from shared_models import (  # loads every message type: only when used
        InvalidNameError,
        resolve_name,
    )

    try:
        return resolve_name(text)
    except InvalidNameError as error:
        raise CliError(str(error)) from None


def known_type(text: str):  # type: ignore[no-untyped-def]
    """The message, service or action class named ``text``; CliError (with "did you mean") if
    none. Besides Skydeck's types: the current folder's workspace packages, then the types the
    core learned from its nodes (a workspace's own messages)."""
    from shared_models import UnknownInterfaceError, get_interface

    use_current_workspace()
    try:
        return get_interface(text)
    except UnknownInterfaceError as error:
        if _learn_from_core(text):
            return known_type(text)
        raise CliError(str(error).splitlines()[0]) from None


def known_type_of(text: str, kind: type, otherwise: str):  # type: ignore[no-untyped-def]
    """The type named ``text`` if it is a ``kind`` (Message, ServiceType, ActionType); else the one
    line ``TEXT OTHERWISE`` (what it is instead and which verb takes it)."""
    found = known_type(text)
    if not issubclass(found, kind):
        raise CliError(f"{text} {otherwise}")
    return found


def use_current_workspace() -> None:
    """Know the packages of the current folder's workspace, as a sourced ROS workspace is known."""
    from shared_models.definitions.index import use_workspace

    use_workspace(Path.cwd())


def _learn_from_core(type_name: str) -> bool:
    from services.cli.core_client import core_url, get
    from services.runtime.core_types import interface_path, is_known, learn_definitions_reply
    from services.runtime.http_client import HttpError

    try:
        reply = get(core_url() + interface_path(type_name), timeout_s=5.0)
        body = reply.json() if reply.status == 200 else None
    except (HttpError, ValueError):
        return False  # no core: the type is unknown, as the caller says
    return learn_definitions_reply(reply.status, body) and is_known(type_name)
