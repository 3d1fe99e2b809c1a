"""The message every topic benchmark sends: a PoseStamped, as a Skydeck message and as plain JSON.

Skydeck, the bare websockets pair and zenoh all carry the same bytes (the JSON of this
PoseStamped). Skydeck serialises each message with pydantic, as a node does; the references
fill a prepared JSON template instead (``frame_template``), the cheapest way to make each frame,
so that they stay the limit (``json.dumps`` of a 64 KiB message takes longer than sending it). Latency runs put the send time in ``header.stamp``: ``time.monotonic_ns()`` is
CLOCK_MONOTONIC, one clock for every process on a Linux machine, so a stamp taken by the
publisher can be subtracted from a reading taken by the subscriber.
"""

from __future__ import annotations

import time

from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, Pose, PoseStamped, Quaternion
from shared_models.std_msgs import Header

__all__ = ["BURST", "TOPIC", "frame_template", "latency_us", "pose_message", "stamp_now", "stamped_frame"]

TOPIC = "/bench/pose"
# Throughput publishers return to their event loop once every BURST messages, Skydeck and the
# bare pair alike: a bare `await websocket.send()` does not suspend while the socket takes the
# data, so yielding after every Skydeck publish would charge Skydeck a loop iteration per message
# that the reference never pays. 10 is well under the subscription queue (100): nothing drops.
BURST = 10
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


_SENTINELS = (987654321, 987654322, 987654323)  # seq, sec, nanosec: unique in the JSON


def frame_template(size_bytes: int | None = None) -> str:
    """The message's JSON with ``%d`` for seq, stamp sec and stamp nanosec (``template % (...)``)."""
    msg = pose_message(size_bytes)
    msg.header.seq, msg.header.stamp.sec, msg.header.stamp.nanosec = _SENTINELS
    text = msg.model_dump_json().replace("%", "%%")
    for sentinel in _SENTINELS:
        if text.count(str(sentinel)) != 1:
            raise ValueError(f"sentinel {sentinel} is not unique in the benchmark message")
        text = text.replace(str(sentinel), "%d")
    return text


def stamp_now(stamp: Time) -> None:
    """Set ``stamp`` to now on the machine-wide monotonic clock (for Skydeck publishers)."""
    now = time.monotonic_ns()
    stamp.sec = now // _NS
    stamp.nanosec = now % _NS


def stamped_frame(template: str, seq: int) -> str:
    """A frame from :func:`frame_template` with ``seq`` and a monotonic stamp of now."""
    now = time.monotonic_ns()
    return template % (seq, now // _NS, now % _NS)


def latency_us(sec: int, nanosec: int) -> float:
    """Microseconds from a stamp (taken by :func:`stamp_now`) to now."""
    return (time.monotonic_ns() - (sec * _NS + nanosec)) / 1000.0
