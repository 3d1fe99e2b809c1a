"""``skydeck topic list | info | type | find | echo | hz | bw | delay | pub`` (rostopic / ros2 topic)."""

from __future__ import annotations

import argparse
import asyncio
import json
import time

from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed, InvalidHandshake

from services.cli.arguments import add_noun, known_type_of, positive_float, positive_int, ros_name
from services.cli.core_client import auth_headers, core_url, get_json, ws_url
from services.cli.errors import CliError
from services.cli.formatting import message_from, message_view, system_name, to_csv, to_yaml
from services.cli.graph import add_graph_verbs, lookup_in_graph, print_sections
from services.cli.streams import check_topic, frames
from services.cli.topic_stats import add_stats_parsers
from shared_models.close_codes import Close

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    verbs = add_noun(subparsers, "topic", "list, inspect, echo and publish topics")

    listed = add_graph_verbs(
        verbs,
        "topic",
        listing=_list,
        list_help="list the topics of the running system",
        info=_info,
        info_help="type, publishers, subscribers and rate of a topic",
        example_type="geometry_msgs/msg/PoseStamped",
    )
    listed.add_argument("-v", "--verbose", action="store_true", help="show publisher and subscriber counts")

    p = verbs.add_parser("echo", help="print the messages of a topic")
    p.add_argument("topic")
    p.add_argument("--once", action="store_true", help="print one message and exit")
    p.add_argument("-n", "--count", type=positive_int, help="exit after N messages")
    p.add_argument("--rate", type=positive_float, help="at most HZ messages a second (newest wins)")
    p.add_argument("--json", action="store_true", help="one JSON object per line instead of YAML")
    p.add_argument("--csv", action="store_true", help="one line of comma-separated values per message")
    p.add_argument("--field", metavar="PATH", help="only this field, e.g. pose.position or ranges[0]")
    p.add_argument("--no-arr", action="store_true", help="print arrays as their length only")
    p.add_argument("--qos-depth", type=positive_int, metavar="N", help="messages the stream keeps while printing (default 100)")
    p.add_argument("--timeout", type=positive_float, help="give up after S seconds without a message")
    p.set_defaults(func=_echo)

    add_stats_parsers(verbs)

    p = verbs.add_parser("pub", help="publish a message (DATA as YAML or JSON)")
    p.add_argument("topic")
    p.add_argument("type", help="message type, e.g. geometry_msgs/msg/Twist")
    p.add_argument("data", nargs="?", default="{}", help='e.g. "{linear: {x: 1.0}}"')
    group = p.add_mutually_exclusive_group()
    group.add_argument("-1", "--once", action="store_true", help="publish one message and exit")
    group.add_argument("-r", "--rate", type=positive_float, default=1.0, help="publish at HZ until Ctrl-C (default 1)")
    p.add_argument("-t", "--times", type=positive_int, help="publish N messages and exit")
    p.set_defaults(func=_pub)


def _list(args: argparse.Namespace) -> int:
    graph = get_json("/api/graph")
    # Nodes of another system a bridge sees (ROS 2's): their topics say so with -t and -v.
    foreign = {node["name"]: node["system"] for node in graph["nodes"] if node.get("system")}
    for topic in graph["topics"]:
        line = topic["name"]
        if args.show_types:
            line += f" [{topic['type']}]"
        if args.verbose:
            line += f" {len(topic['publishers'])} publisher(s), {len(topic['subscribers'])} subscriber(s)"
        systems = sorted({foreign[p] for p in topic["publishers"] if p in foreign})
        if systems and (args.show_types or args.verbose):
            line += f" (from {', '.join(system_name(s) for s in systems)})"
        print(line)
    return 0


def _info(args: argparse.Namespace) -> int:
    topic, graph = lookup_in_graph("topic", ros_name(args.topic))
    urls = {node["name"]: node["url"] for node in graph["nodes"]}
    print(f"Type: {topic['type']}")
    if topic.get("rate_hz") is not None:
        print(f"Rate: {topic['rate_hz']:.2f} Hz")
    print_sections(topic, (("Publishers", "publishers"), ("Subscribers", "subscribers")), lambda node: f"({urls.get(node, '?')})")
    return 0


def _echo(args: argparse.Namespace) -> int:
    name = ros_name(args.topic)
    limit = 1 if args.once else args.count
    # A bounded echo (a script's "give me a message") fails on a name the system lacks; a stream,
    # or one given --timeout, waits for a publisher to come, as rostopic and ros2 topic wait.
    check_topic(name, wait=limit is None or args.timeout is not None)
    show = message_view(field=args.field, no_arr=args.no_arr)

    async def run() -> None:
        printed = 0
        async with asyncio.timeout(args.timeout):
            async for frame in frames(name, rate=args.rate, queue=args.qos_depth):
                if args.json and show is None:
                    print(frame, flush=True)
                else:
                    value = json.loads(frame) if show is None else show(json.loads(frame))
                    if args.csv:
                        print(to_csv(value), flush=True)
                    elif args.json:
                        print(json.dumps(value, separators=(",", ":")), flush=True)
                    else:
                        print(to_yaml(value) + "\n---", flush=True)
                printed += 1
                if limit is not None and printed >= limit:
                    return

    try:
        asyncio.run(run())
    except TimeoutError:
        raise CliError(f"no message on {name} within {args.timeout:g} s") from None
    return 0


def _pub(args: argparse.Namespace) -> int:
    # The message types and the validation, here and not at the top: see cli/interface.py.
    from shared_models import Message

    name = ros_name(args.topic)
    msg_type = known_type_of(args.type, Message, "is a service type: use `skydeck service call`")
    msg = message_from(args.data, msg_type)
    topics = {t["name"]: t for t in get_json("/api/graph")["topics"]}
    if name in topics and topics[name]["type"] != msg_type.__ros_type__:
        raise CliError(f"{name} is {topics[name]['type']}, not {msg_type.__ros_type__}")
    frame = msg.model_dump_json()
    count = 1 if args.once else args.times
    print(f"publisher: beginning loop\npublishing #1: {msg_type.__name__}({frame})", flush=True)

    async def run() -> None:
        url = ws_url(name, type=msg_type.__ros_type__)
        async with connect(url, additional_headers=auth_headers(), compression=None) as websocket:
            sent = 0
            period_s = 1.0 / args.rate
            next_send = time.monotonic()
            while count is None or sent < count:
                await websocket.send(frame)
                sent += 1
                next_send += period_s
                if count is not None and sent >= count:
                    break
                await asyncio.sleep(max(0.0, next_send - time.monotonic()))
            await websocket.close()
            if websocket.close_code not in (Close.NORMAL, None):
                raise CliError(f"the core refused the message ({websocket.close_code}): {websocket.close_reason}")

    try:
        asyncio.run(run())
    except (OSError, InvalidHandshake) as error:
        raise CliError(f"cannot reach the core at {core_url()}: {error}") from None
    except ConnectionClosed as closed:
        reason = closed.rcvd.reason if closed.rcvd else "connection lost"
        raise CliError(f"the core closed the topic: {reason}") from None
    return 0
