"""``skydeck node list | info`` (rosnode / ros2 node)."""

from __future__ import annotations

import argparse

from services.cli.arguments import node_name
from services.cli.core_client import get_json

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    node = subparsers.add_parser("node", help="list and inspect nodes")
    verbs = node.add_subparsers(dest="verb", required=True, metavar="VERB")
    p = verbs.add_parser("list", help="list the running nodes")
    p.set_defaults(func=_list)
    p = verbs.add_parser("info", help="URL, pid, publications, subscriptions and services of a node")
    p.add_argument("node")
    p.set_defaults(func=_info)


def _list(args: argparse.Namespace) -> int:
    for node in get_json("/api/graph")["nodes"]:
        print(node["name"])
    return 0


def _info(args: argparse.Namespace) -> int:
    name = node_name(args.node)
    node = get_json(f"/api/nodes{name}", missing=f"unknown node {name}: see `skydeck node list`")
    graph = get_json("/api/graph")
    types = {t["name"]: t["type"] for t in graph["topics"]}
    types.update({s["name"]: s["type"] for s in graph["services"]})
    print("-" * 80)
    print(f"Node [{node['name']}]\nURI: {node['url']}\nPid: {node['pid']}")
    if node.get("client"):  # a client of the core shown as a node (rosbridge, Foxglove)
        print(f"Client: {node['client']}")
    for title, key in (("Publications", "publications"), ("Subscriptions", "subscriptions"), ("Services", "services")):
        print(f"\n{title}:")
        if not node[key]:
            print(" None")
        for entity in node[key]:
            print(f" * {entity} [{types.get(entity, '?')}]")
    return 0
