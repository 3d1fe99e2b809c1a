"""The message every topic benchmark sends: a PoseStamped, as a Skydeck message and as plain JSON.

Skydeck, the bare websockets pair and zenoh all carry the same bytes (the JSON of this
PoseStamped). Latency runs put the send time in ``header.stamp``: ``time.monotonic_ns()`` is
CLOCK_MONOTONIC, one clock for every process on a Linux machine, so a stamp taken by the
publisher can be subtracted from a reading taken by the subscriber.
"""

from __future__ import annotations

import json
import time
from typing import Any

from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, Pose, PoseStamped, Quaternion
from shared_models.std_msgs import Header

__all__ = ["TOPIC", "latency_us", "pose_dict", "pose_message", "stamp_now", "stamped_dict_json"]

TOPIC = "/bench/pose"
_NS = 1_000_000_000


def pose_message(size_bytes: int | None = None) -> PoseStamped:
    """The benchmark's PoseStamped; ``size_bytes`` pads ``frame_id`` so the JSON is that long."""
    msg = PoseStamped(
        header=Header(stamp=Time(sec=0, nanosec=0), frame_id="map"),
        pose=Pose(
            position=Point(x=1.2345678, y=-2.3456789, z=3.0123456),
            orientation=Quaternion(x=0.0, y=0.0, z=0.3826834, w=0.9238795),
        ),
    )
    if size_bytes is not None:
        missing = size_bytes - len(msg.model_dump_json())
        if missing > 0:
            msg.header.frame_id = "map" + "_" * missing
    return msg


def pose_dict(size_bytes: int | None = None) -> dict[str, Any]:
    """The same message as a plain dict (what a bare client builds), JSON-identical."""
    return json.loads(pose_message(size_bytes).model_dump_json())


def stamp_now(stamp: Time) -> None:
    """Set ``stamp`` to now on the machine-wide monotonic clock."""
    now = time.monotonic_ns()
    stamp.sec = now // _NS
    stamp.nanosec = now % _NS


def stamped_dict_json(payload: dict[str, Any], seq: int) -> str:
    """The JSON of ``payload`` with ``seq`` and a monotonic stamp of now (for bare publishers)."""
    header = payload["header"]
    now = time.monotonic_ns()
    header["seq"] = seq
    header["stamp"]["sec"] = now // _NS
    header["stamp"]["nanosec"] = now % _NS
    return json.dumps(payload, separators=(",", ":"))


def latency_us(sec: int, nanosec: int) -> float:
    """Microseconds from a stamp (taken by :func:`stamp_now`) to now."""
    return (time.monotonic_ns() - (sec * _NS + nanosec)) / 1000.0
