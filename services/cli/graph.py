"""What the graph verbs share (``topic``, ``service``, ``node``): one entity by name, and the
lookup verbs of topics and services (``info``, ``type``, ``find``), registered alike."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import Any, Literal

from services.cli.arguments import known_type, ros_name
from services.cli.core_client import get_json
from services.cli.errors import CliError

__all__ = ["add_lookup_verbs", "lookup"]

Noun = Literal["topic", "service", "node"]
Handler = Callable[[argparse.Namespace], int]


def lookup(noun: Noun, name: str) -> dict[str, Any]:
    """The core's record of the topic, service or node ``name``; an unknown one is a CliError
    that says how to list them."""
    return get_json(f"/api/{noun}s{name}", missing=f"unknown {noun} {name}: see `skydeck {noun} list`")  # type: ignore[no-any-return]


def add_lookup_verbs(
    verbs: argparse._SubParsersAction[argparse.ArgumentParser],
    noun: Literal["topic", "service"],
    *,
    info_help: str,
    info: Handler,
    example_type: str,
) -> None:
    """``NOUN info NAME`` (``info``), ``NOUN type NAME`` and ``NOUN find TYPE``."""
    p = verbs.add_parser("info", help=info_help)
    p.add_argument(noun)
    p.set_defaults(func=info)

    p = verbs.add_parser("type", help=f"the type of a {noun}")
    p.add_argument(noun)
    p.set_defaults(func=lambda args: _print_type(noun, getattr(args, noun)))

    p = verbs.add_parser("find", help=f"the {noun}s of a type")
    p.add_argument("type", help=f"e.g. {example_type}")
    p.set_defaults(func=lambda args: _print_names_of_type(noun, args.type))


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
