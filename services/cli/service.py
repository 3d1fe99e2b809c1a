"""``skydeck service list | info | type | find | call`` (rosservice / ros2 service)."""

from __future__ import annotations

import argparse

from services.cli.arguments import add_noun, ros_name
from services.cli.core_client import error_detail, get_json, post_json, unknown_name
from services.cli.errors import CliError
from services.cli.formatting import parse_data, to_yaml
from services.cli.graph import add_graph_verbs, lookup

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    verbs = add_noun(subparsers, "service", "list, inspect and call services")

    listed = add_graph_verbs(
        verbs,
        "service",
        listing=_list,
        list_help="list the services of the running system: the world's commands first, then parameter services",
        info=_info,
        info_help="node, URL and type of a service",
        example_type="std_srvs/srv/Trigger",
    )
    listed.add_argument(
        "-a", "--all", action="store_true", help="also Skydeck's own services (rosapi's, the launch's), listed last"
    )

    p = verbs.add_parser("call", help="call a service (DATA as YAML or JSON, default {})")
    p.add_argument("service")
    p.add_argument("data", nargs="?", default="{}", help='e.g. "{x: 5.0, y: -3.0}"')
    p.add_argument("--timeout", type=float, default=15.0, help="seconds to wait for the answer (default 15)")
    p.set_defaults(func=_call)


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
    service = lookup("service", ros_name(args.service))
    print(f"Node: {service['node']}\nURI: {service['url']}{service['name']}\nType: {service['type']}")
    return 0


def _call(args: argparse.Namespace) -> int:
    name = ros_name(args.service)
    reply = post_json(name, parse_data(args.data), timeout_s=args.timeout)
    if reply.status == 404:  # no such service (or topic): the nearest ones it has
        raise CliError(unknown_name("service", name)())
    if reply.status != 200:
        raise CliError(f"{name}: {error_detail(reply)} (HTTP {reply.status})")
    print(to_yaml(reply.json()))
    return 0
