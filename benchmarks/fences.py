"""The fences' cost per message: a student publishing through a class's core, against anyone
publishing through a core with no class (the same client, messages and topic shape, same run).

    python -m benchmarks.fences --messages 20000 --mode class   # one RESULT line

A fresh ``skydeck core`` (with ``--class-tokens`` for ``class``, its students' rate limits set
out of reach so that nothing is shed) gets ``messages`` Twist frames on one publishing socket
(``?mode=publish``) as fast as the client sends them, while a second socket reads the topic
(``queue=10000``) until the last frame arrives. Measured: the core's CPU time per message. In a
class the socket is admitted once and each frame costs its student's rate count; the decision
itself is made at the first frame. The in-process cost of that count (``Pass.spend``) is
measured too, for the detail.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
import tempfile
import timeit
from pathlib import Path
from typing import Any

from websockets.asyncio.client import connect

from benchmarks.processes import Worker, start_core, worker_env
from services.access import RateLimits, make_class_tokens, write_tokens
from services.runtime.edge.links import stream_url

__all__ = ["measure_fences", "spend_ns"]

_TYPE = "geometry_msgs/msg/Twist"
_TIMEOUT_S = 120.0


def _start_core(mode: str, folder: Path) -> tuple[Worker, str, str]:
    """A core with no class (``open``) or a class of one student (``class``); its URL and the
    token to publish with."""
    if mode == "open":
        return (*start_core("fences-core-open"), "")
    tokens = make_class_tokens(["alice"])
    path = folder / "class-tokens.csv"
    write_tokens(path, tokens)
    limits = {"SKYDECK_STUDENT_MESSAGES_PER_S": "1e12", "SKYDECK_STUDENT_BYTES_PER_S": "1e15"}  # nothing is shed
    worker, url = start_core("fences-core-class", flags=("--class-tokens", str(path)), env=worker_env(**limits))
    return worker, url, tokens["alice"]


async def _publish(url: str, token: str, messages: int) -> None:
    topic = "/alice/bench_cmd_vel"
    auth = {"token": token} if token else {}
    reader_url = stream_url(url, topic, mode="subscribe", queue=10_000, **auth)
    writer_url = stream_url(url, topic, mode="publish", type=_TYPE, **auth)
    last = json.dumps({"linear": {"x": float(messages), "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}})
    async with connect(reader_url, max_size=None) as reader, connect(writer_url) as writer:
        frames = [
            json.dumps({"linear": {"x": float(i), "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}})
            for i in range(1, messages)
        ]
        async with asyncio.timeout(_TIMEOUT_S):
            for frame in frames:
                await writer.send(frame)
            await writer.send(last)
            while json.loads(await reader.recv())["linear"]["x"] != float(messages):
                pass


def _cpu_s(pid: int) -> float:
    """The CPU time of every thread of process ``pid`` so far, to the nanosecond (Linux's
    schedstat: the clock ticks of /proc/PID/stat are 10 ms, a fence's cost a few hundred ns)."""
    total = 0
    for task in Path(f"/proc/{pid}/task").iterdir():
        try:
            total += int((task / "schedstat").read_text().split()[0])
        except (OSError, ValueError, IndexError):
            continue  # a thread that ended meanwhile
    return total / 1e9


def measure_fences(messages: int, mode: str) -> dict[str, Any]:
    """The core's CPU time per message published through it, with (``class``) or without (``open``) a class."""
    with tempfile.TemporaryDirectory() as folder:
        worker, url, token = _start_core(mode, Path(folder))
        try:
            asyncio.run(_publish(url, token, 200))  # warm: the topic, the type, the links
            before = _cpu_s(worker.pid)
            asyncio.run(_publish(url, token, messages))
            cpu = _cpu_s(worker.pid) - before
        finally:
            worker.stop()
    return {"mode": mode, "messages": messages, "core_cpu_s": cpu, "us_per_message": 1e6 * cpu / messages}


def spend_ns(repeat: int = 200_000) -> float:
    """What a student's message costs the fences in-process: one rate count (ns)."""
    bucket = RateLimits(messages_per_s=1e12, bytes_per_s=1e15, calls_in_flight=1).bucket("alice")
    return 1e9 * min(timeit.repeat(lambda: bucket.spend(100), number=repeat, repeat=3)) / repeat


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--messages", type=int, default=20_000)
    parser.add_argument("--mode", choices=["open", "class"], default="class")
    args = parser.parse_args()
    sys.stdout.write("RESULT " + json.dumps(measure_fences(args.messages, args.mode)) + "\n")


if __name__ == "__main__":
    main()
