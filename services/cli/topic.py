"""``skydeck topic list | info | echo | hz | pub`` (rostopic / ros2 topic)."""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import time
from collections import deque

from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed, InvalidHandshake, InvalidStatus

from services.cli.arguments import positive_float, positive_int, ros_name
from services.cli.core_client import auth_headers, core_url, get_json, ws_url
from services.cli.errors import CliError
from services.cli.formatting import parse_data, to_yaml

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    topic = subparsers.add_parser("topic", help="list, inspect, echo and publish topics")
    verbs = topic.add_subparsers(dest="verb", required=True, metavar="VERB")

    p = verbs.add_parser("list", help="list the topics of the running system")
    p.add_argument("-t", "--show-types", action="store_true", help="show each topic's type")
    p.add_argument("-v", "--verbose", action="store_true", help="show publisher and subscriber counts")
    p.set_defaults(func=_list)

    p = verbs.add_parser("info", help="type, publishers, subscribers and rate of a topic")
    p.add_argument("topic")
    p.set_defaults(func=_info)

    p = verbs.add_parser("echo", help="print the messages of a topic")
    p.add_argument("topic")
    p.add_argument("--once", action="store_true", help="print one message and exit")
    p.add_argument("-n", "--count", type=positive_int, help="exit after N messages")
    p.add_argument("--rate", type=positive_float, help="at most HZ messages a second (newest wins)")
    p.add_argument("--json", action="store_true", help="one JSON object per line instead of YAML")
    p.add_argument("--timeout", type=positive_float, help="give up after S seconds without a message")
    p.set_defaults(func=_echo)

    p = verbs.add_parser("hz", help="print the publishing rate of a topic")
    p.add_argument("topic")
    p.add_argument("-w", "--window", type=positive_int, default=100, help="messages in the rate window")
    p.add_argument("-n", "--count", type=positive_int, help="exit after N reports")
    p.set_defaults(func=_hz)

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
    for topic in get_json("/api/graph")["topics"]:
        line = topic["name"]
        if args.show_types:
            line += f" [{topic['type']}]"
        if args.verbose:
            line += f" {len(topic['publishers'])} publisher(s), {len(topic['subscribers'])} subscriber(s)"
        print(line)
    return 0


def _info(args: argparse.Namespace) -> int:
    name = ros_name(args.topic)
    topic = get_json(f"/api/topics{name}", missing=f"unknown topic {name}: see `skydeck topic list`")
    graph = get_json("/api/graph")
    urls = {node["name"]: node["url"] for node in graph["nodes"]}
    print(f"Type: {topic['type']}")
    if topic.get("rate_hz") is not None:
        print(f"Rate: {topic['rate_hz']:.2f} Hz")
    for title, key in (("Publishers", "publishers"), ("Subscribers", "subscribers")):
        print(f"\n{title}:")
        if not topic[key]:
            print(" None")
        for node in topic[key]:
            print(f" * {node} ({urls.get(node, '?')})")
    return 0


async def _frames(name: str, *, rate: float | None = None, queue: int | None = None):  # type: ignore[no-untyped-def]
    url = ws_url(name, rate=rate, queue=queue)
    try:
        async with connect(url, additional_headers=auth_headers(), compression=None, max_size=None) as websocket:
            async for frame in websocket:
                yield frame
            if websocket.close_code not in (1000, 1001, None):
                raise CliError(f"{name}: the core closed the stream ({websocket.close_code}): {websocket.close_reason}")
    except (OSError, InvalidHandshake, TimeoutError) as error:
        if isinstance(error, InvalidStatus):
            raise CliError(f"the core refused the stream of {name}: HTTP {error.response.status_code}") from None
        raise CliError(
            f"cannot reach the core at {core_url()}: is it running? start it with `skydeck core` (or `make up`)"
        ) from None


def _warn_if_unpublished(name: str) -> None:
    topics = {t["name"]: t for t in get_json("/api/graph")["topics"]}
    if name not in topics or not topics[name]["publishers"]:
        print(f"WARNING: topic [{name}] does not appear to be published yet", flush=True)


def _echo(args: argparse.Namespace) -> int:
    name = ros_name(args.topic)
    _warn_if_unpublished(name)
    limit = 1 if args.once else args.count

    async def run() -> None:
        printed = 0
        async with asyncio.timeout(args.timeout):
            async for frame in _frames(name, rate=args.rate):
                if args.json:
                    print(frame, flush=True)
                else:
                    print(to_yaml(json.loads(frame)) + "\n---", flush=True)
                printed += 1
                if limit is not None and printed >= limit:
                    return

    try:
        asyncio.run(run())
    except TimeoutError:
        raise CliError(f"no message on {name} within {args.timeout:g} s") from None
    return 0


def _hz(args: argparse.Namespace) -> int:
    name = ros_name(args.topic)
    _warn_if_unpublished(name)

    async def run() -> None:
        arrivals: deque[float] = deque(maxlen=args.window + 1)

        async def count_arrivals() -> None:
            # Its own task: a report's deadline must never cancel a read (that ends the stream).
            async for _ in _frames(name, queue=10_000):
                arrivals.append(time.monotonic())

        reader = asyncio.create_task(count_arrivals())
        try:
            reports = 0
            next_report = time.monotonic() + 1.0
            while args.count is None or reports < args.count:
                await asyncio.wait({reader}, timeout=max(0.0, next_report - time.monotonic()))
                if reader.done():
                    reader.result()  # the stream ended: its error, if any, is the CLI's error
                    return
                next_report += 1.0
                _print_rate(arrivals)
                reports += 1
        finally:
            reader.cancel()

    asyncio.run(run())
    return 0


def _print_rate(arrivals: deque[float]) -> None:
    if len(arrivals) < 2:
        print("no new messages", flush=True)
        return
    gaps = [b - a for a, b in zip(arrivals, list(arrivals)[1:], strict=False)]
    mean = sum(gaps) / len(gaps)
    std = math.sqrt(sum((g - mean) ** 2 for g in gaps) / len(gaps))
    print(f"average rate: {1.0 / mean:.3f}", flush=True)
    print(f"\tmin: {min(gaps):.3f}s max: {max(gaps):.3f}s std dev: {std:.5f}s window: {len(gaps)}", flush=True)


def _pub(args: argparse.Namespace) -> int:
    # The message types and the validation, here and not at the top: see cli/interface.py.
    from pydantic import ValidationError

    from services.runtime.edge.frames import describe_validation_error
    from shared_models import Message, UnknownInterfaceError, get_interface

    name = ros_name(args.topic)
    try:
        msg_type = get_interface(args.type)
    except UnknownInterfaceError as error:
        raise CliError(str(error).splitlines()[0]) from None
    if not issubclass(msg_type, Message):
        raise CliError(f"{args.type} is a service type: use `skydeck service call`")
    try:
        msg = msg_type.model_validate(parse_data(args.data))
    except ValidationError as error:
        raise CliError(describe_validation_error(msg_type.__ros_type__, error)) from None
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
            if websocket.close_code not in (1000, None):
                raise CliError(f"the core refused the message ({websocket.close_code}): {websocket.close_reason}")

    try:
        asyncio.run(run())
    except (OSError, InvalidHandshake) as error:
        raise CliError(f"cannot reach the core at {core_url()}: {error}") from None
    except ConnectionClosed as closed:
        reason = closed.rcvd.reason if closed.rcvd else "connection lost"
        raise CliError(f"the core closed the topic: {reason}") from None
    return 0
