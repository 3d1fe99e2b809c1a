"""Worker: the peer, a zenoh publisher and subscriber (``eclipse-zenoh``) in peer mode over TCP.

    python -m benchmarks.topic_zenoh sub --port P     # listens on tcp/127.0.0.1:P; READY
    python -m benchmarks.topic_zenoh pub --port P     # connects, waits for a match, publishes

The same JSON bytes, made from a prepared template and decoded with ``json.loads`` per message,
as the bare websockets pair does. Scouting is off and the endpoint explicit, so the two find
each other at once and nothing else on the machine joins in.
"""

from __future__ import annotations

import argparse
import json
import threading
import time
from typing import Any

import zenoh

from benchmarks.payload import frame_template, stamped_frame
from benchmarks.sink import Sink, emit, topic_arguments, wait_for_stop

_KEY = "bench/pose"
_MATCH_TIMEOUT_S = 10.0


def _config(endpoint: str, *, listen: bool) -> zenoh.Config:
    config = zenoh.Config()
    config.insert_json5("mode", '"peer"')
    config.insert_json5("listen/endpoints" if listen else "connect/endpoints", json.dumps([endpoint]))
    if not listen:
        config.insert_json5("listen/endpoints", "[]")
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("scouting/gossip/enabled", "false")
    return config


def _matched(pub: zenoh.Publisher) -> bool:
    # A MatchingStatus at run time (its stub says bool): true once a subscriber matches.
    status: Any = pub.matching_status
    return bool(getattr(status, "matching", status))


def publisher(args: argparse.Namespace) -> None:
    template = frame_template(args.size)
    with zenoh.open(_config(f"tcp/127.0.0.1:{args.port}", listen=False)) as session:
        pub = session.declare_publisher(_KEY)
        deadline = time.monotonic() + _MATCH_TIMEOUT_S
        while not _matched(pub):
            if time.monotonic() > deadline:
                raise SystemExit("zenoh publisher found no subscriber")
            time.sleep(0.01)
        emit("READY", {})
        cpu_start, start = time.process_time(), time.monotonic()
        sent = 0
        if args.mode == "throughput":
            end = start + args.duration
            put = pub.put
            while time.monotonic() < end:
                sent += 1
                put((template % (sent, 0, 0)).encode())
        else:
            period_s = 1.0 / args.rate
            while (now := time.monotonic()) - start < args.duration:
                due = start + sent * period_s
                if due > now:
                    time.sleep(due - now)
                sent += 1
                pub.put(stamped_frame(template, sent).encode())
        wall_s, cpu_s = time.monotonic() - start, time.process_time() - cpu_start
        time.sleep(0.3)
        emit("RESULT", {"sent": sent, "wall_s": wall_s, "cpu_s": cpu_s, "rate": sent / wall_s})
        pub.undeclare()


def subscriber(args: argparse.Namespace) -> None:
    sink = Sink(args.mode, args.warmup)
    latency = args.mode == "latency"
    loads = json.loads
    lock = threading.Lock()  # zenoh may call back from more than one thread

    def on_sample(sample: Any) -> None:
        data = loads(sample.payload.to_bytes())
        with lock:
            if latency:
                stamp = data["header"]["stamp"]
                sink.arrive(stamp["sec"], stamp["nanosec"])
            else:
                sink.arrive()

    with zenoh.open(_config(f"tcp/127.0.0.1:{args.port}", listen=True)) as session:
        sub = session.declare_subscriber(_KEY, on_sample)
        emit("READY", {})
        wait_for_stop()
        sub.undeclare()
        with lock:
            emit("RESULT", sink.summary())


def main() -> None:
    args = topic_arguments(__doc__.splitlines()[0]).parse_args()
    publisher(args) if args.role == "pub" else subscriber(args)


if __name__ == "__main__":
    main()
