"""What the graph verbs share (``topic``, ``service``, ``node``): one entity by name, ``info``'s
lists, and the verbs topics and services have alike (``list``, ``info``, ``type``, ``find``)."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import Any, Literal

from services.cli.arguments import known_type, ros_name
from services.cli.core_client import get_json, unknown_name
from services.cli.errors import CliError

__all__ = ["add_graph_verbs", "lookup", "lookup_in_graph", "print_sections"]

Noun = Literal["topic", "service", "node"]
Handler = Callable[[argparse.Namespace], int]


def lookup(noun: Noun, name: str) -> dict[str, Any]:
    """The core's record of the topic, service or node ``name``; an unknown one is a CliError
    with the nearest names the system has, and how to list them."""
    return get_json(f"/api/{noun}s{name}", missing=unknown_name(noun, name))  # type: ignore[no-any-return]


def lookup_in_graph(noun: Noun, name: str) -> tuple[dict[str, Any], dict[str, Any]]:
    """The record of ``name`` (:func:`lookup`) and the whole graph, for ``info``'s cross references
    (a node's entities' types, a topic's publishers' URLs)."""
    return lookup(noun, name), get_json("/api/graph")


def print_sections(record: dict[str, Any], sections: tuple[tuple[str, str], ...], describe: Callable[[str], str]) -> None:
    """``info``'s lists, as rosnode and rostopic print them: each section's title, then each entry
    with what ``describe`` says of it, or ``None``."""
    for title, key in sections:
        print(f"\n{title}:")
        if not record[key]:
            print(" None")
        for entry in record[key]:
            print(f" * {entry} {describe(entry)}")


def add_graph_verbs(
    verbs: argparse._SubParsersAction[argparse.ArgumentParser],
    noun: Literal["topic", "service"],
    *,
    listing: Handler,
    list_help: str,
    info: Handler,
    info_help: str,
    example_type: str,
) -> argparse.ArgumentParser:
    """``NOUN list [-t]`` (``listing``), ``NOUN info NAME`` (``info``), ``NOUN type NAME`` and
    ``NOUN find TYPE``; returns ``list``'s parser, for the flags of the noun's own."""
    listed = verbs.add_parser("list", help=list_help)
    listed.add_argument("-t", "--show-types", action="store_true", help=f"show each {noun}'s type")
    listed.set_defaults(func=listing)

    p = verbs.add_parser("info", help=info_help)
    p.add_argument(noun)
    p.set_defaults(func=info)

    p = verbs.add_parser("type", help=f"the type of a {noun}")
    p.add_argument(noun)
    p.set_defaults(func=lambda args: _print_type(noun, getattr(args, noun)))

    p = verbs.add_parser("find", help=f"the {noun}s of a type")
    p.add_argument("type", help=f"e.g. {example_type}")
    p.set_defaults(func=lambda args: _print_names_of_type(noun, args.type))
    return listed


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
