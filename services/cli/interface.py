"""``skydeck interface list | show | proto`` (ros2 interface)."""

from __future__ import annotations

import argparse

from services.cli.arguments import add_noun, add_verb, known_type, use_current_workspace
from services.cli.formatting import to_yaml

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    verbs = add_noun(subparsers, "interface", "list and show message, service and action types")
    p = verbs.add_parser("list", help="list every known type")
    kind = p.add_mutually_exclusive_group()
    kind.add_argument("-m", "--only-msgs", action="store_true", help="only message types")
    kind.add_argument("-s", "--only-srvs", action="store_true", help="only service types")
    kind.add_argument("-a", "--only-actions", action="store_true", help="only action types")
    p.set_defaults(func=_list)
    p = add_verb(verbs, "show", _show, "show a type's fields, nested types indented")
    p.add_argument("type", help="e.g. geometry_msgs/msg/PointStamped")
    add_verb(verbs, "proto", _proto, "a default instance of a message type, as YAML to edit", "type")


# shared_models is imported by each verb, not at the top: every `skydeck` command builds this
# parser, and most never need the message types.


def _lookup(name: str):  # type: ignore[no-untyped-def]
    return known_type(name)


def _list(args: argparse.Namespace) -> int:
    from shared_models import interface_names
    from shared_models.definitions.index import index
    from shared_models.definitions.loader import load_package

    use_current_workspace()
    for package in index.interface_packages(shipped=False):  # the workspace's own, as ROS lists them
        load_package(package.name)
    kind = "msg" if args.only_msgs else "srv" if args.only_srvs else "action" if args.only_actions else None
    for name in interface_names(kind):
        print(name)
    return 0


def _show(args: argparse.Namespace) -> int:
    from shared_models import interface_text

    print(interface_text(_lookup(args.type)))
    return 0


def _proto(args: argparse.Namespace) -> int:
    from shared_models import ActionType, Message

    cls = _lookup(args.type)
    if issubclass(cls, ActionType):
        cls = cls.Goal
    elif not issubclass(cls, Message):
        cls = cls.Request
    print(to_yaml(cls().model_dump(mode="json")))
    return 0
