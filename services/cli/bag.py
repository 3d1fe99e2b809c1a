"""``skydeck bag record | info | play`` (rosbag / ros2 bag), on MCAP files."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import re
import shlex
import signal
import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from services.cli.arguments import add_noun, add_verb, known_type, positive_float, ros_name
from services.cli.core_client import core_url, get_json, node_settings
from services.cli.errors import CliError

if TYPE_CHECKING:
    from services.runtime.node import Node

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    verbs = add_noun(subparsers, "bag", "record topics to an MCAP file, show it, play it back")

    p = verbs.add_parser("record", help="record topics into an MCAP file until Ctrl-C")
    p.add_argument("topics", nargs="*", metavar="TOPIC", help="topics to record (they may appear later)")
    p.add_argument("-a", "--all", action="store_true", help="every topic, also those that appear later")
    p.add_argument("-o", "--output", metavar="PATH", help="the file (.mcap added if missing; default skydeck_DATE-TIME.mcap)")
    p.add_argument("-x", "--exclude", metavar="REGEX", help="leave out topics this regular expression matches")
    p.add_argument("--max-duration", type=positive_float, metavar="S", help="stop after S seconds")
    p.add_argument("--max-size", type=positive_float, metavar="MB", help="stop once the file reaches MB megabytes")
    p.add_argument(
        "--encoding", choices=("json", "cdr"), default="json",
        help="json (default: frames as received, for Foxglove) or cdr (ROS 2's: the ros2 profile, for rosbag2)",
    )
    p.set_defaults(func=_record)

    p = add_verb(verbs, "info", _info, "duration, times, message count and topics of a recording")
    p.add_argument("file", metavar="FILE")

    p = add_verb(verbs, "play", _play, "publish a recording again, with its timing")
    p.add_argument("file", metavar="FILE")
    p.add_argument("-r", "--rate", type=positive_float, default=1.0, help="speed factor (default 1)")
    p.add_argument("-l", "--loop", action="store_true", help="play again from the start when done, until Ctrl-C")
    p.add_argument("--start-offset", type=_seconds, default=0.0, metavar="S", help="skip the first S seconds")
    p.add_argument("--topics", nargs="+", metavar="TOPIC", help="only these topics")
    p.add_argument("--clock", action="store_true", help="publish /clock from the recording (for use_sim_time nodes)")
    p.add_argument("--clock-hz", type=positive_float, default=100.0, metavar="HZ", help="/clock rate when the recording has none (default 100)")
    p.add_argument("--remap", action="append", default=[], metavar="FROM:=TO", help="publish topic FROM as TO (repeatable)")
    p.add_argument("--wait-for-subscribers", action="store_true", help="start once every topic has a subscriber")


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not (value >= 0 and value != float("inf")):
        raise argparse.ArgumentTypeError(f"expected 0 or more seconds, got {text!r}")
    return value


# -- record ---------------------------------------------------------------------------------


def _record(args: argparse.Namespace) -> int:
    from services.bag.recorder import Recorder
    from services.bag.recording import Limits, TopicSelection
    from services.bag.writer import BagWriter, bag_path

    if args.all and args.topics:
        raise CliError("give topics to record or -a for all of them, not both")
    try:
        exclude = re.compile(args.exclude) if args.exclude else None
    except re.error as error:
        raise CliError(f"--exclude {args.exclude!r} is not a regular expression: {error}") from None
    selection = TopicSelection(
        all_topics=args.all, topics=frozenset(ros_name(name) for name in args.topics), exclude=exclude
    )
    limits = Limits(
        duration_s=args.max_duration,
        size_bytes=int(args.max_size * 1_000_000) if args.max_size is not None else None,
    )
    path = bag_path(args.output or time.strftime("skydeck_%Y_%m_%d-%H_%M_%S"))
    metadata = _metadata()  # also checks that the core answers, before a file is made
    writer = BagWriter.create(path, metadata=metadata, encoding=args.encoding)
    print(f"recording to {path} (Ctrl-C stops)", flush=True)
    recorder = Recorder(writer, selection, limits=limits, settings=node_settings(), say=_say)
    try:
        _run(recorder)
    finally:
        writer.close()
    counts = writer.counts()
    size = path.stat().st_size
    from services.bag.info import format_size

    print(
        f"recorded {writer.message_count} messages on {len(counts)} topics to {path} ({format_size(size)})",
        flush=True,
    )
    return 0


def _metadata() -> dict[str, str]:
    from importlib.metadata import PackageNotFoundError, version

    get_json("/api/graph")  # the core must answer: a recorder without one records nothing
    world = _latest("/simulator/world")
    try:
        skydeck_version = version("skydeck")
    except PackageNotFoundError:
        skydeck_version = "unknown"
    metadata = {
        "skydeck_version": skydeck_version,
        "command_line": shlex.join(["skydeck", *sys.argv[1:]]),
        "core_url": core_url(),
        "started": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
    }
    if world:
        metadata["world_seed"] = str(world.get("seed", ""))
        metadata["world_id"] = str(world.get("id", ""))
    return metadata


def _latest(topic: str) -> dict[str, Any] | None:
    try:
        value = get_json(topic, missing="")
    except CliError:
        return None
    return value if isinstance(value, dict) else None


# -- info -----------------------------------------------------------------------------------


def _info(args: argparse.Namespace) -> int:
    from services.bag.info import format_info
    from services.bag.reader import BagReader

    with BagReader(args.file) as reader:
        print(format_info(reader.summary))
        _warn_if_recovered(reader)
    return 0


def _warn_if_recovered(reader: Any) -> None:
    if reader.summary.recovered:
        print(
            f"skydeck: warning: {reader.path} was not finished (its recorder was stopped abruptly): "
            f"read up to its last complete chunk",
            file=sys.stderr,
            flush=True,
        )


# -- play -----------------------------------------------------------------------------------


def _play(args: argparse.Namespace) -> int:
    from services.bag import BagReader, Player, PlayOptions, check_types
    from services.bag.keyboard import space_bar

    options = PlayOptions(
        rate=args.rate,
        loop=args.loop,
        start_offset_s=args.start_offset,
        topics=frozenset(ros_name(name) for name in args.topics) if args.topics else None,
        clock=args.clock,
        clock_hz=args.clock_hz,
        remap=dict(_remap(text) for text in args.remap),
        wait_for_subscribers=args.wait_for_subscribers,
    )
    with BagReader(args.file) as reader:
        _warn_if_recovered(reader)
        for topic in reader.summary.topics:  # a workspace's own types: the folder's, or the core's
            with contextlib.suppress(CliError):
                known_type(topic.type_name)
        player = Player(reader, options, settings=node_settings(), say=_say)
        check_types(get_json("/api/graph")["topics"], player.played_types)
        summary = reader.summary
        print(
            f"playing {args.file}: {summary.message_count} messages on {len(player.topics)} topics, "
            f"{summary.duration_s:.3f} s at rate {args.rate:g}",
            flush=True,
        )

        _run(player, lambda: space_bar(player.toggle_pause))
        print(f"played {player.played} messages", flush=True)
    return 0


def _remap(text: str) -> tuple[str, str]:
    source, separator, target = text.partition(":=")
    if not separator or not source or not target:
        raise CliError(f"--remap takes FROM:=TO, got {text!r}")
    return ros_name(source), ros_name(target)


# -- running a node -------------------------------------------------------------------------


def _say(line: str) -> None:
    print(line, flush=True)


def _run(node: Node, keys: Callable[[], contextlib.AbstractContextManager[bool]] | None = None) -> bool:
    """Run ``node`` until it stops by itself or Ctrl-C / SIGTERM asks; True if a signal did."""
    from services.runtime.executor import configure_logging

    configure_logging("WARNING")
    interrupted = False

    async def main() -> None:
        nonlocal interrupted
        loop = asyncio.get_running_loop()

        def stop() -> None:
            nonlocal interrupted
            interrupted = True
            node.destroy_node()

        for sig in (signal.SIGINT, signal.SIGTERM):
            with contextlib.suppress(NotImplementedError, RuntimeError):
                loop.add_signal_handler(sig, stop)
        with keys() if keys is not None else contextlib.nullcontext():
            await node.run_until_stopped()

    asyncio.run(main())
    return interrupted
