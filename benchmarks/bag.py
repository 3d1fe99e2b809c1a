"""Recording and playback, measured: what ``skydeck bag record`` keeps up with, and how
closely ``skydeck bag play`` keeps the recorded timing.

- **world**: the simulator at ``--speed max`` and ``skydeck bag record -a``, every topic of the
  drone world; every stamped topic's ``header.seq`` and ``/clock``'s steps say how many
  messages were published while recording, against how many are in the file.
- **throughput**: a publisher of small stamped frames (110 B, already serialised, as fast as it
  can) and ``skydeck bag record /bench/small``: messages written per second of the recording,
  and the share of what was published (the publisher keeps 10,000 frames for a slower
  recorder, then drops the oldest, as ROS's queue does).
- **playback**: a recording of two stamped topics (100 Hz and 30 Hz, made here) played by
  ``skydeck bag play`` to a listener node; each message's arrival against its recorded time,
  the median offset taken out, so what is left is the player's timing error plus transport.
"""

from __future__ import annotations

import json
import signal
import tempfile
import time
from pathlib import Path
from typing import Any

from benchmarks.processes import BenchError, Worker, free_port, wait_http, worker_env
from benchmarks.sim import sim_argv
from benchmarks.sink import percentile
from benchmarks.topics import CoreHolder
from services.bag.reader import BagReader
from services.bag.writer import BagWriter

__all__ = ["measure_playback_timing", "measure_record_throughput", "measure_record_world"]

_STOP_TIMEOUT_S = 20.0


def _recorder(env: dict[str, str], path: Path, *topics: str) -> Worker:
    worker = Worker("bag-record", "services.cli", "bag", "record", *topics, "-o", str(path), env=env)
    try:
        worker.wait_for_line(lambda line: line.startswith("recording to"), 30.0)
    except Exception as error:
        worker.stop()
        raise BenchError(f"skydeck bag record did not start: {error}") from None
    return worker


def _finish(worker: Worker) -> None:
    if not worker.stop(signal.SIGINT, timeout_s=_STOP_TIMEOUT_S) or worker.returncode != 0:
        raise BenchError(f"skydeck bag record did not finish cleanly: {worker.tail(5)}")


def measure_record_throughput(core: CoreHolder, *, duration_s: float) -> dict[str, Any]:
    """Small messages as fast as a publisher makes them, recorded: msg/s written, share kept."""
    env = worker_env(core.get())
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "throughput.mcap"
        recorder = _recorder(env, path, "/bench/small")
        try:
            with Worker("bag-pub", "benchmarks.bag_worker", "publish", "/bench/small", str(duration_s), env=env) as publisher:
                publisher.expect("READY", 30.0)
                cpu_before = recorder.cpu_seconds()
                sent = publisher.expect("RESULT", duration_s + 30.0)
                cpu_s = recorder.cpu_seconds() - cpu_before
        finally:
            _finish(recorder)
        with BagReader(path) as bag:
            times = [message.log_time_ns for message in bag.messages(["/bench/small"])]
    if len(times) < 2:
        raise BenchError("the recorder wrote nothing of /bench/small")
    span_s = (times[-1] - times[0]) / 1e9
    return {
        "rate": len(times) / span_s,
        "recorded": len(times),
        "sent": sent["sent"],
        "kept": len(times) / sent["sent"],
        "publisher_rate": sent["rate"],
        "recorder_cpu": cpu_s / sent["wall_s"],
        "recorder_us_per_msg": cpu_s / sent["sent"] * 1e6,  # what a core can keep up with: 1e6 / this
    }


def measure_record_world(core: CoreHolder, *, window_s: float, boxes: int = 8, seed: int = 1) -> dict[str, Any]:
    """Every topic of the drone world at speed max, recorded; published vs in the file, per topic."""
    env = worker_env(core.get())
    port = free_port()
    argv = sim_argv(port, seed=seed, boxes=boxes)
    with tempfile.TemporaryDirectory() as folder, Worker("bag-sim", argv=argv, env=env) as sim:
        wait_http(f"http://127.0.0.1:{port}/clock", 60.0, what="simulator /clock", worker=sim)
        path = Path(folder) / "world.mcap"
        recorder = _recorder(env, path, "-a")
        try:
            recorder.wait_for_line(lambda line: "subscribed to /drone/pose" in line, 30.0)
            time.sleep(window_s)  # a window of the world running flat out, nothing to await
        finally:
            _finish(recorder)
        with BagReader(path) as bag:
            summary = bag.summary
            per_topic = {topic.topic: _kept(bag, topic.topic) for topic in summary.topics if topic.count >= 2}
            duration_s = summary.duration_s
    checked = {topic: kept for topic, kept in per_topic.items() if kept is not None}
    if "/drone/pose" not in checked:
        raise BenchError("the recording has no /drone/pose to check")
    return {
        "kept": min(checked.values()),
        "per_topic": checked,
        "messages": summary.message_count,
        "rate": summary.message_count / duration_s if duration_s else 0.0,
        "topics": len(summary.topics),
    }


def _kept(bag: BagReader, topic: str) -> float | None:
    """Recorded / published, from header.seq (stamped topics) or /clock's steps; None if unknowable."""
    frames = [json.loads(message.frame) for message in bag.messages([topic])]
    if isinstance(frames[0].get("header"), dict) and "seq" in frames[0]["header"]:
        seqs = [frame["header"]["seq"] for frame in frames]
        return len(frames) / (seqs[-1] - seqs[0] + 1)
    if topic == "/clock":
        ns = [frame["sec"] * 1_000_000_000 + frame["nanosec"] for frame in frames]
        step = min(b - a for a, b in zip(ns, ns[1:], strict=False) if b > a)
        return len(frames) / (round((ns[-1] - ns[0]) / step) + 1)
    return None


def measure_playback_timing(core: CoreHolder, *, seconds: float = 3.0, rate: float = 1.0) -> dict[str, Any]:
    """Timing error of ``bag play`` at a listener: p50/p99/max of |arrival - recorded| (median offset out)."""
    env = worker_env(core.get())
    with tempfile.TemporaryDirectory() as folder:
        path = _timing_bag(Path(folder) / "timing.mcap", seconds)
        with BagReader(path) as bag:
            recorded = {(m.topic, m.sequence): m.log_time_ns / 1e9 for m in bag.messages()}
        with Worker("bag-listen", "benchmarks.bag_worker", "listen", "/bench/fast", "/bench/slow", env=env) as listener:
            listener.expect("READY", 30.0)
            player = Worker(
                "bag-play", "services.cli", "bag", "play", str(path), "--wait-for-subscribers", "--rate", str(rate), env=env
            )
            try:
                player.wait_for_line(lambda line: line.startswith("played"), seconds / rate + 60.0)
            finally:
                player.stop(timeout_s=10.0)
            time.sleep(0.2)  # the last frames are on their way
            listener.send("stop")
            arrivals = listener.expect("RESULT", 30.0)["arrivals"]
    if len(arrivals) != len(recorded):
        raise BenchError(f"the listener got {len(arrivals)} of {len(recorded)} played messages")
    first_recorded = min(recorded.values())
    offsets = sorted(at - (recorded[(topic, seq)] - first_recorded) / rate for topic, seq, at in arrivals)
    median = offsets[len(offsets) // 2]
    errors_ms = sorted(abs(offset - median) * 1e3 for offset in offsets)
    return {
        "p50_ms": percentile(errors_ms, 0.5),
        "p99_ms": percentile(errors_ms, 0.99),
        "max_ms": errors_ms[-1],
        "messages": len(errors_ms),
    }


def _timing_bag(path: Path, seconds: float) -> Path:
    """Two stamped topics, 100 Hz and 30 Hz, interleaved, ``seconds`` long."""
    from shared_models.geometry_msgs import PointStamped
    from shared_models.std_msgs import Header

    writer = BagWriter.create(path, metadata={"command_line": "skydeck bench"})
    start_ns = time.time_ns()
    events = []
    for topic, hz in (("/bench/fast", 100.0), ("/bench/slow", 30.0)):
        channel = writer.add_topic(topic, "geometry_msgs/msg/PointStamped")
        for index in range(int(seconds * hz)):
            events.append((start_ns + int(index * 1e9 / hz), channel, index + 1))
    for log_ns, channel, seq in sorted(events):
        writer.write(channel, PointStamped(header=Header(seq=seq, frame_id="map")).model_dump_json(), log_ns)
    writer.close()
    return path
