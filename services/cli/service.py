"""``skydeck service list | info | type | find | call`` (rosservice / ros2 service)."""

from __future__ import annotations

import argparse

from services.cli.arguments import known_type, ros_name
from services.cli.core_client import error_detail, get_json, post_json, unknown_name
from services.cli.errors import CliError
from services.cli.formatting import parse_data, to_yaml

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    service = subparsers.add_parser("service", help="list, inspect and call services")
    verbs = service.add_subparsers(dest="verb", required=True, metavar="VERB")

    p = verbs.add_parser(
        "list",
        help="list the services of the running system: the world's commands first, then parameter services",
    )
    p.add_argument("-t", "--show-types", action="store_true", help="show each service's type")
    p.add_argument(
        "-a", "--all", action="store_true", help="also Skydeck's own services (rosapi's, the launch's), listed last"
    )
    p.set_defaults(func=_list)

    p = verbs.add_parser("info", help="node, URL and type of a service")
    p.add_argument("service")
    p.set_defaults(func=_info)

    p = verbs.add_parser("type", help="the type of a service")
    p.add_argument("service")
    p.set_defaults(func=_type)

    p = verbs.add_parser("find", help="the services of a type")
    p.add_argument("type", help="e.g. std_srvs/srv/Trigger")
    p.set_defaults(func=_find)

    p = verbs.add_parser("call", help="call a service (DATA as YAML or JSON, default {})")
    p.add_argument("service")
    p.add_argument("data", nargs="?", default="{}", help='e.g. "{x: 5.0, y: -3.0}"')
    p.add_argument("--timeout", type=float, default=15.0, help="seconds to wait for the answer (default 15)")
    p.set_defaults(func=_call)


def _lookup(name: str) -> dict[str, str]:
    return get_json(f"/api/services{name}", missing=unknown_name("service", name))  # type: ignore[no-any-return]


def _list(args: argparse.Namespace) -> int:
    from services.runtime.service_groups import ServiceGroup, service_group

    # The world's commands lead; the nodes' parameter services follow, as `ros2 service list`
    # lists them too; Skydeck's own (rosapi for rosbridge clients, the launch's) only with --all,
    # as ros2 lists hidden services only when asked.
    grouped = sorted((service_group(s["name"], s["node"]), s["name"], s["type"]) for s in get_json("/api/graph")["services"])
    for group, name, type_name in grouped:
        if group is ServiceGroup.SYSTEM and not args.all:
            continue
        print(name + (f" [{type_name}]" if args.show_types else ""))
    return 0


def _info(args: argparse.Namespace) -> int:
    service = _lookup(ros_name(args.service))
    print(f"Node: {service['node']}\nURI: {service['url']}{service['name']}\nType: {service['type']}")
    return 0


def _type(args: argparse.Namespace) -> int:
    print(_lookup(ros_name(args.service))["type"])
    return 0


def _find(args: argparse.Namespace) -> int:
    from shared_models import ServiceType

    found = known_type(args.type)
    if not issubclass(found, ServiceType):
        raise CliError(f"{found.__ros_type__} is a message type: use `skydeck topic find`")
    for service in get_json("/api/graph")["services"]:
        if service["type"] == found.__ros_type__:
            print(service["name"])
    return 0


def _call(args: argparse.Namespace) -> int:
    name = ros_name(args.service)
    reply = post_json(name, parse_data(args.data), timeout_s=args.timeout)
    if reply.status_code == 404:  # no such service (or topic): the nearest ones it has
        raise CliError(unknown_name("service", name)())
    if reply.status_code != 200:
        raise CliError(f"{name}: {error_detail(reply)} (HTTP {reply.status_code})")
    print(to_yaml(reply.json()))
    return 0
