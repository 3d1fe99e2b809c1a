"""What the graph verbs share (``topic``, ``service``, ``node``): one entity by name, ``info``'s
lists, and the verbs topics and services have alike (``list``, ``info``, ``type``, ``find``)."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import Any, Literal

from services.cli.arguments import known_type, ros_name
from services.cli.core_client import get_json
from services.cli.errors import CliError
from services.cli.formatting import system_name

__all__ = ["add_graph_verbs", "lookup", "print_sections"]

Noun = Literal["topic", "service", "node"]
Handler = Callable[[argparse.Namespace], int]


def lookup(noun: Noun, name: str) -> dict[str, Any]:
    """The core's record of the topic, service or node ``name``; an unknown one is a CliError
    that says how to list them."""
    return get_json(f"/api/{noun}s{name}", missing=f"unknown {noun} {name}: see `skydeck {noun} list`")  # type: ignore[no-any-return]


def print_sections(record: dict[str, Any], sections: tuple[tuple[str, str], ...], describe: Callable[[str], str]) -> None:
    """``info``'s lists, as rosnode and rostopic print them: each section's title, then each entry
    with what ``describe`` says of it, or ``None``."""
    for title, key in sections:
        print(f"\n{title}:")
        if not record[key]:
            print(" None")
        for entry in record[key]:
            print(f" * {entry} {describe(entry)}")


def _print_list(noun: Literal["topic", "service"], show_types: bool, verbose: bool) -> int:
    graph = get_json("/api/graph")
    # Nodes of another system a bridge sees (ROS 2's): the topics they publish say so with -t and -v.
    foreign = {node["name"]: node["system"] for node in graph["nodes"] if node.get("system")}
    for entity in graph[noun + "s"]:
        line = entity["name"]
        if show_types:
            line += f" [{entity['type']}]"
        if verbose:
            line += f" {len(entity['publishers'])} publisher(s), {len(entity['subscribers'])} subscriber(s)"
        systems = sorted({foreign[p] for p in entity.get("publishers", ()) if p in foreign})
        if systems and (show_types or verbose):
            line += f" (from {', '.join(system_name(s) for s in systems)})"
        print(line)
    return 0


def add_graph_verbs(
    verbs: argparse._SubParsersAction[argparse.ArgumentParser],
    noun: Literal["topic", "service"],
    *,
    info_help: str,
    info: Handler,
    example_type: str,
) -> argparse.ArgumentParser:
    """``NOUN list [-t]``, ``NOUN info NAME`` (``info``), ``NOUN type NAME`` and ``NOUN find
    TYPE``; returns ``list``'s parser (a ``-v`` added there counts a topic's publishers and
    subscribers)."""
    listing = verbs.add_parser("list", help=f"list the {noun}s of the running system")
    listing.add_argument("-t", "--show-types", action="store_true", help=f"show each {noun}'s type")
    listing.set_defaults(func=lambda args: _print_list(noun, args.show_types, getattr(args, "verbose", False)))

    p = verbs.add_parser("info", help=info_help)
    p.add_argument(noun)
    p.set_defaults(func=info)

    p = verbs.add_parser("type", help=f"the type of a {noun}")
    p.add_argument(noun)
    p.set_defaults(func=lambda args: _print_type(noun, getattr(args, noun)))

    p = verbs.add_parser("find", help=f"the {noun}s of a type")
    p.add_argument("type", help=f"e.g. {example_type}")
    p.set_defaults(func=lambda args: _print_names_of_type(noun, args.type))
    return listing


def _print_type(noun: Literal["topic", "service"], name: str) -> int:
    print(lookup(noun, ros_name(name))["type"])
    return 0


def _print_names_of_type(noun: Literal["topic", "service"], type_name: str) -> int:
    from shared_models import Message, ServiceType

    found = known_type(type_name)  # an unknown name is an error, not "none found"
    if noun == "topic" and not issubclass(found, Message):
        raise CliError(f"{found.__ros_type__} is a service type: use `skydeck service find`")
    if noun == "service" and not issubclass(found, ServiceType):
        raise CliError(f"{found.__ros_type__} is a message type: use `skydeck topic find`")
    for entity in get_json("/api/graph")[noun + "s"]:
        if entity["type"] == found.__ros_type__:
            print(entity["name"])
    return 0
