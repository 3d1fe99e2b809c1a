"""``skydeck topic hz | bw | delay``: a report a second over a window of the latest messages
(rostopic / ros2 topic), each reading the topic's stream through the core in msgpack (they
print no message, so they need no JSON: the core sends an image as 0.9 MB of bytes, not 1.2 MB
of base64 text, and the CLI reads a stamp without parsing text)."""

from __future__ import annotations

import argparse
import asyncio
import math
import time
from collections import deque
from collections.abc import Callable, Coroutine
from typing import Any

import ormsgpack

from services.cli.arguments import positive_int, ros_name
from services.cli.errors import CliError
from services.cli.streams import check_topic, frames

__all__ = ["add_stats_parsers"]

_REPORT_PERIOD_S = 1.0


def add_stats_parsers(verbs: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    for verb, what, func in (
        ("hz", "the publishing rate of a topic", _hz),
        ("bw", "the bandwidth a topic uses", _bw),
        ("delay", "the delay from each message's header stamp to its arrival", _delay),
    ):
        p = verbs.add_parser(verb, help=f"print {what}, once a second")
        p.add_argument("topic")
        p.add_argument("-w", "--window", type=positive_int, default=100, help="messages in the window (default 100)")
        p.add_argument("-n", "--count", type=positive_int, help="exit after N reports")
        if verb == "delay":
            p.add_argument(
                "--use-sim-time", action="store_true", help="compare stamps with /clock instead of the wall clock"
            )
        p.set_defaults(func=func)


def _run(
    args: argparse.Namespace,
    on_frame: Callable[[bytes, float], None],
    report: Callable[[], None],
    *,
    alongside: Callable[[], Coroutine[Any, Any, None]] | None = None,
) -> int:
    """Read the topic, calling ``on_frame(frame, arrival)``; ``report()`` every second, -n times.
    ``alongside()`` runs as long as the reading does (another stream to follow)."""
    name = ros_name(args.topic)
    check_topic(name)

    async def run() -> None:
        async def read() -> None:
            # Its own task: a report's deadline must never cancel a read (that ends the stream).
            async for frame in frames(name, queue=10_000, packed=True):
                on_frame(frame, time.time())

        async def read_all() -> None:
            if alongside is None:
                await read()
                return
            helper = asyncio.ensure_future(alongside())
            try:
                await read()
            finally:
                helper.cancel()

        reader = asyncio.create_task(read_all())
        try:
            reports = 0
            next_report = time.monotonic() + _REPORT_PERIOD_S
            while args.count is None or reports < args.count:
                await asyncio.wait({reader}, timeout=max(0.0, next_report - time.monotonic()))
                if reader.done():
                    reader.result()  # the stream ended: its error, if any, is the CLI's error
                    return
                next_report += _REPORT_PERIOD_S
                report()
                reports += 1
        finally:
            reader.cancel()

    asyncio.run(run())
    return 0


def _spread(values: list[float]) -> tuple[float, float]:
    mean = sum(values) / len(values)
    return mean, math.sqrt(sum((v - mean) ** 2 for v in values) / len(values))


def _hz(args: argparse.Namespace) -> int:
    arrivals: deque[float] = deque(maxlen=args.window + 1)

    def report() -> None:
        if len(arrivals) < 2:
            print("no new messages", flush=True)
            return
        gaps = [b - a for a, b in zip(arrivals, list(arrivals)[1:], strict=False)]
        mean, std = _spread(gaps)
        print(f"average rate: {1.0 / mean:.3f}" if mean > 0 else "average rate: inf", flush=True)
        print(f"\tmin: {min(gaps):.3f}s max: {max(gaps):.3f}s std dev: {std:.5f}s window: {len(gaps)}", flush=True)

    return _run(args, lambda _, at: arrivals.append(at), report)


def _kilobytes(size: float) -> str:
    return f"{size / 1000:.2f} KB" if size < 1_000_000 else f"{size / 1_000_000:.2f} MB"


def _bw(args: argparse.Namespace) -> int:
    window: deque[tuple[float, int]] = deque(maxlen=args.window)

    def report() -> None:
        if len(window) < 2:
            print("no new messages", flush=True)
            return
        sizes = [size for _, size in window]
        span = window[-1][0] - window[0][0]
        rate = sum(sizes[1:]) / span if span > 0 else math.inf
        print(f"{_kilobytes(rate)}/s from {len(sizes)} messages", flush=True)
        print(
            f"\tMessage size mean: {_kilobytes(sum(sizes) / len(sizes))} min: {_kilobytes(min(sizes))} "
            f"max: {_kilobytes(max(sizes))}",
            flush=True,
        )

    return _run(args, lambda frame, at: window.append((at, len(frame))), report)


def _delay(args: argparse.Namespace) -> int:
    name = ros_name(args.topic)
    delays: deque[float] = deque(maxlen=args.window)
    sim_now: list[float] = []

    def on_frame(frame: bytes, arrival: float) -> None:
        message = ormsgpack.unpackb(frame)
        header = message.get("header") if isinstance(message, dict) else None
        if not isinstance(header, dict) or not isinstance(header.get("stamp"), dict):
            raise CliError(f"{name} has no header.stamp: `topic delay` needs stamped messages (try `topic hz`)")
        stamp = header["stamp"].get("sec", 0) + header["stamp"].get("nanosec", 0) * 1e-9
        now = sim_now[0] if args.use_sim_time and sim_now else arrival
        if not args.use_sim_time or sim_now:
            delays.append(now - stamp)

    def report() -> None:
        if not delays:
            print("no new messages" + (" (is /clock published?)" if args.use_sim_time and not sim_now else ""), flush=True)
            return
        mean, std = _spread(list(delays))
        print(f"average delay: {mean:.3f}", flush=True)
        print(f"\tmin: {min(delays):.3f}s max: {max(delays):.3f}s std dev: {std:.5f}s window: {len(delays)}", flush=True)

    async def follow_clock() -> None:
        async for frame in frames("/clock", packed=True):
            clock = ormsgpack.unpackb(frame)
            sim_now[:] = [clock.get("sec", 0) + clock.get("nanosec", 0) * 1e-9]

    return _run(args, on_frame, report, alongside=follow_clock if args.use_sim_time else None)
