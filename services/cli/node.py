"""``skydeck node list | info | ping | kill`` (rosnode / ros2 node)."""

from __future__ import annotations

import argparse
import os
import signal
import time

from services.cli.arguments import add_noun, add_verb, node_name, positive_float, positive_int
from services.cli.core_client import error_detail, get, get_json, post_json
from services.cli.errors import CliError
from services.cli.formatting import system_name
from services.cli.graph import lookup, lookup_in_graph, print_sections
from services.runtime.http_client import HttpError, HttpReply

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    verbs = add_noun(subparsers, "node", "list and inspect nodes")
    add_verb(verbs, "list", _list, "list the running nodes")
    add_verb(verbs, "info", _info, "URL, pid, publications, subscriptions and services of a node", "node")
    p = add_verb(verbs, "ping", _ping, "check that a node answers, and how fast", "node")
    p.add_argument("-c", "--count", type=positive_int, default=1, help="pings to send (default 1)")
    p.add_argument("--timeout", type=positive_float, default=3.0, help="seconds to wait for each answer (default 3)")
    add_verb(verbs, "kill", _kill, "stop a node for good: its launch does not respawn it", "node")


def _list(args: argparse.Namespace) -> int:
    for node in get_json("/api/graph")["nodes"]:
        # A node of another system, seen through a bridge (a ROS 2 node): marked, name first
        print(f"{node['name']} ({system_name(node['system'])}, via {node['via']})" if node.get("system") else node["name"])
    return 0


def _info(args: argparse.Namespace) -> int:
    node, graph = lookup_in_graph("node", node_name(args.node))
    types = {t["name"]: t["type"] for t in graph["topics"]}
    types.update({s["name"]: s["type"] for s in graph["services"]})
    print("-" * 80)
    print(f"Node [{node['name']}]\nURI: {node['url']}\nPid: {node['pid']}")
    if node.get("client"):  # a client of the core shown as a node (rosbridge, Foxglove)
        print(f"Client: {node['client']}")
    if node.get("system"):  # another system's node, seen through a bridge
        print(f"System: {system_name(node['system'])}, via {node['via']}")
    sections = (("Publications", "publications"), ("Subscriptions", "subscriptions"), ("Services", "services"))
    print_sections(node, sections, lambda entity: f"[{types.get(entity, '?')}]")
    return 0


def _ping(args: argparse.Namespace) -> int:
    name = node_name(args.node)
    url = lookup("node", name)["url"].rstrip("/")
    print(f"pinging {name} with a timeout of {args.timeout:g}s", flush=True)
    failed = 0
    for attempt in range(args.count):
        started = time.perf_counter()
        reply: HttpReply | None = None
        try:
            reply = get(url + "/health", timeout_s=args.timeout)
            ok = reply.status == 200
        except HttpError as error:
            ok = False
            print(f"ERROR: connection to {url} failed: {error}", flush=True)
        if ok:
            print(f"reply from {url} time={(time.perf_counter() - started) * 1e3:.3f}ms", flush=True)
        else:
            failed += 1
            if reply is not None:
                print(f"ERROR: {url}/health answered {reply.status}", flush=True)
        if attempt + 1 < args.count:
            time.sleep(1.0)
    if failed:
        raise CliError(f"{name} did not answer {failed} of {args.count} ping(s): is its process alive? see `skydeck node info {name}`")
    return 0


def _kill(args: argparse.Namespace) -> int:
    from services.launch.control import KILL_SERVICE, LAUNCH_NODE
    from shared_models.skydeck_launch import KillNodeResponse

    name = node_name(args.node)
    node = lookup("node", name)
    if name in ("/skydeck_core", LAUNCH_NODE):
        raise CliError(f"{name} is part of Skydeck itself: stop the core or the launch with Ctrl-C")
    services = {service["name"] for service in get_json("/api/graph")["services"]}
    if KILL_SERVICE in services:
        reply = post_json(KILL_SERVICE, {"node": name}, timeout_s=15.0)
        if reply.status != 200:
            raise CliError(f"the launch could not be asked: {error_detail(reply)} (HTTP {reply.status})")
        answer = KillNodeResponse.model_validate(reply.json())
        if answer.success:
            print(answer.message)
            return 0
        if answer.reason != KillNodeResponse.NOT_LAUNCHED:  # started elsewhere: stopped here if it runs here
            raise CliError(answer.message or f"the launch refused ({answer.reason})")
    return _kill_local(name, node)


def _kill_local(name: str, node: dict) -> int:  # type: ignore[type-arg]
    """A node no launch started (`skydeck run` in a terminal): SIGTERM its process, if it is here."""
    url = node.get("url", "")
    pid = node.get("pid")
    if not isinstance(pid, int) or not any(host in url for host in ("://127.0.0.1", "://localhost", "://[::1]")):
        raise CliError(f"{name} runs at {url}, not on this machine, and no launch manages it: stop it where it runs")
    try:
        os.kill(pid, signal.SIGTERM)
    except ProcessLookupError:
        raise CliError(f"{name} (pid {pid}) is not running any more") from None
    except PermissionError:
        raise CliError(f"not allowed to stop {name} (pid {pid}): it belongs to another user") from None
    print(f"killed {name} (pid {pid}) with SIGTERM")
    return 0
