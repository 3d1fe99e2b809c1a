"""Heavy data and many viewers: a camera and a hundred browsers on one core, and what an
encoding costs per message.

- classroom: a publisher node of poses (60 Hz) and 640x480 images (raw and JPEG, 30 Hz), and
  100 pose viewers (JSON) plus 20 raw-image viewers (msgpack) reading through the core;
  delivery is each viewer's rate against the publisher's, latency from the publish stamp.
- the same with 5 stalled image readers (they open a socket and never read): the others'
  delivery should not change.
- 20 JPEG viewers.
- encoding cost: one 640x480 image and one pose, JSON (base64, as rosbridge) against msgpack,
  made and read in this process.
"""

from __future__ import annotations

import statistics
import time
from typing import Any

from benchmarks.processes import Worker, worker_env
from benchmarks.topics import CoreHolder
from benchmarks.viewers_worker import IMAGE

__all__ = ["encoding_costs", "run_classroom"]

_POSE_HZ = 60.0


def run_classroom(
    core: CoreHolder, *, duration_s: float, pose: int, image: int, stalled: int = 0, topic: str = IMAGE, image_hz: float = 30.0
) -> dict[str, Any]:
    """One classroom run; delivery as fractions of what was published, latencies in ms."""
    url = core.get()
    env = worker_env(url)
    with Worker("viewers-publisher", "benchmarks.viewers_worker", "publisher", "--image-hz", str(image_hz), env=env) as camera:
        camera.expect("READY", 30.0)
        with Worker(
            "viewers",
            "benchmarks.viewers_worker",
            "viewers", "--core", url, "--pose", str(pose), "--image", str(image),
            "--stalled", str(stalled), "--image-topic", topic,
            env=env,
        ) as crowd:  # fmt: skip
            crowd.expect("READY", 60.0)
            started = time.monotonic()
            core_cpu = core.cpu_seconds()
            time.sleep(duration_s)
            core_cpu = core.cpu_seconds() - core_cpu
            crowd.send("stop")
            camera.send("stop")
            seen = crowd.expect("RESULT", 30.0)
            sent = camera.expect("RESULT", 30.0)
    wall = time.monotonic() - started
    image_hz_sent = sent["published"][topic] / sent["wall_s"]
    return {
        "pose_delivery": min(seen["pose"]["rates"], default=0.0) / _POSE_HZ if pose else None,
        "pose_p99_ms": seen["pose"]["p99_us"] / 1000 if pose else None,
        "image_delivery": min(seen["image"]["rates"], default=0.0) / image_hz_sent if image else None,
        "image_p50_ms": seen["image"]["p50_us"] / 1000 if image else None,
        "image_p99_ms": seen["image"]["p99_us"] / 1000 if image else None,
        "core_cpu": core_cpu / wall,
        "publisher_cpu": sent["cpu"],
    }


def encoding_costs(repeats: int = 20) -> dict[str, float]:
    """Milliseconds to make and to read one message, JSON against msgpack (median of repeats)."""
    from benchmarks.viewers_worker import _image
    from services.runtime.edge.encoding import Encoding, decode, encode
    from shared_models.geometry_msgs import PoseStamped

    raw, _ = _image(640, 480)
    results: dict[str, float] = {}
    for name, msg in (("image", raw), ("pose", PoseStamped())):
        for encoding in Encoding:
            made, read = [], []
            for _ in range(repeats if name == "image" else repeats * 100):
                started = time.perf_counter()
                frame = encode(msg, encoding)
                made.append(time.perf_counter() - started)
                started = time.perf_counter()
                decode(frame, type(msg), msg.__ros_type__)
                read.append(time.perf_counter() - started)
            results[f"{name}_{encoding.value}_ms"] = 1000 * (statistics.median(made) + statistics.median(read))
            results[f"{name}_{encoding.value}_bytes"] = len(encode(msg, encoding))
    return results

