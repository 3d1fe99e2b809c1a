"""What a benchmark subscriber records, and the worker side of the line protocol.

Every topic worker (Skydeck, bare websockets, zenoh) counts and times arrivals with the same
:class:`Sink` and speaks the same protocol (``READY``/``RESULT`` lines out, ``stop`` in), so
the three differ only in their transport.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import sys
import time
from typing import Any

from benchmarks.payload import latency_us

__all__ = ["Sink", "counting_window", "emit", "percentile", "topic_arguments", "wait_for_stop", "wait_for_stop_async"]

_MAX_SAMPLES_KEPT = 20_000  # latency samples sent back for the plots


def emit(tag: str, data: dict[str, Any] | None = None) -> None:
    """Print one protocol line (``READY {...}`` or ``RESULT {...}``) to stdout."""
    sys.stdout.write(f"{tag} {json.dumps(data or {})}\n")
    sys.stdout.flush()


def wait_for_stop() -> None:
    """Block until the runner writes ``stop`` (or closes stdin)."""
    for line in sys.stdin:
        if line.strip() == "stop":
            return


async def wait_for_stop_async() -> None:
    """:func:`wait_for_stop` without blocking the event loop."""
    await asyncio.to_thread(wait_for_stop)


async def counting_window(tasks: list[asyncio.Task[Any]], counting: asyncio.Event, warmup_s: float) -> float:
    """A crowd of readers' measured window: after ``warmup_s`` they count (``counting`` is set)
    and ``READY`` is said; at ``stop`` they are cancelled. Returns the window's wall seconds."""
    await asyncio.sleep(warmup_s)
    counting.set()
    emit("READY", {})
    started = time.monotonic()
    await wait_for_stop_async()
    wall = time.monotonic() - started
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    return wall


def percentile(sorted_values: list[float], fraction: float) -> float:
    """The ``fraction`` quantile (nearest rank) of already sorted values."""
    if not sorted_values:
        return float("nan")
    index = min(len(sorted_values) - 1, max(0, round(fraction * (len(sorted_values) - 1))))
    return sorted_values[index]


def topic_arguments(description: str) -> argparse.ArgumentParser:
    """The flags every topic worker takes."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("role", choices=["pub", "sub"])
    parser.add_argument("--mode", choices=["throughput", "latency"], default="throughput")
    parser.add_argument("--duration", type=float, default=2.0, help="seconds of publishing")
    parser.add_argument("--rate", type=float, default=1000.0, help="messages/s in latency mode")
    parser.add_argument("--warmup", type=float, default=0.3, help="seconds not counted at the start")
    parser.add_argument("--size", type=int, default=None, help="pad the JSON to this many bytes")
    parser.add_argument("--port", type=int, default=0)
    parser.add_argument("--topic", default="/bench/pose", help="Skydeck subscriber: topic to read")
    parser.add_argument("--type", default="geometry_msgs/msg/PoseStamped", help="Skydeck subscriber: its type")
    parser.add_argument("--subscribers", type=int, default=1, help="publisher waits for this many")
    return parser


class Sink:
    """Counts arrivals (throughput) or collects publish-to-callback latencies (latency)."""

    def __init__(self, mode: str, warmup_s: float) -> None:
        self.latency = mode == "latency"
        self.warmup_s = warmup_s
        self.received = 0
        self.counted = 0
        self._first: float | None = None
        self._window_start: float | None = None
        self._last = 0.0
        self._latencies: list[float] = []

    def arrive(self, sec: int = 0, nanosec: int = 0) -> None:
        """One message arrived (with its send stamp, in latency mode)."""
        now = time.monotonic()
        self.received += 1
        if self._first is None:
            self._first = now
        if now - self._first < self.warmup_s:
            return
        if self._window_start is None:
            self._window_start = now
        self.counted += 1
        self._last = now
        if self.latency:
            self._latencies.append(latency_us(sec, nanosec))

    def summary(self) -> dict[str, Any]:
        """What the runner needs: a rate, or latency percentiles and (thinned) samples."""
        result: dict[str, Any] = {"received": self.received, "counted": self.counted}
        span = self._last - self._window_start if self._window_start is not None else 0.0
        result["rate"] = (self.counted - 1) / span if span > 0 else 0.0
        if self.latency:
            values = sorted(self._latencies)
            step = max(1, len(self._latencies) // _MAX_SAMPLES_KEPT)
            result.update(
                p50_us=percentile(values, 0.50),
                p90_us=percentile(values, 0.90),
                p99_us=percentile(values, 0.99),
                max_us=values[-1] if values else float("nan"),
                mean_us=statistics.fmean(values) if values else float("nan"),
                samples_us=self._latencies[::step],
            )
        return result
