"""Plane geometry the criteria share: where a track was at a time, how long it is, how far a
point is from a box or a segment. Pure functions over :class:`~services.grading.tracks.Pose`."""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence

from services.grading.shapes import Box, Pose

__all__ = ["distance_to_box", "distance_to_segment", "path_length", "position_at", "speeds"]


def position_at(track: Sequence[Pose], t: float) -> tuple[float, float]:
    """Where ``track`` (sorted by time) was at ``t``: linear between samples, its ends outside them."""
    if not track:
        raise ValueError("an empty track was never anywhere")
    times = [pose.t for pose in track]
    i = bisect.bisect_left(times, t)
    if i == 0:
        return track[0].x, track[0].y
    if i == len(track):
        return track[-1].x, track[-1].y
    a, b = track[i - 1], track[i]
    f = (t - a.t) / (b.t - a.t) if b.t > a.t else 0.0
    return a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)


def path_length(track: Sequence[Pose], *, start_s: float = -math.inf, end_s: float = math.inf) -> float:
    """Metres travelled along ``track`` between two times (horizontal)."""
    total = 0.0
    for a, b in zip(track, track[1:], strict=False):
        if a.t >= start_s and b.t <= end_s:
            total += math.hypot(b.x - a.x, b.y - a.y)
    return total


def speeds(track: Sequence[Pose]) -> list[tuple[float, float]]:
    """(t, m/s) between consecutive samples, at the later one."""
    return [
        (b.t, math.hypot(b.x - a.x, b.y - a.y) / (b.t - a.t))
        for a, b in zip(track, track[1:], strict=False)
        if b.t > a.t
    ]


def distance_to_box(x: float, y: float, box: Box) -> float:
    """Metres from (x, y) to the nearest point of ``box`` (0 inside it)."""
    c, s = math.cos(box.yaw), math.sin(box.yaw)
    dx, dy = x - box.x, y - box.y
    local_x, local_y = c * dx + s * dy, -s * dx + c * dy
    out_x = max(abs(local_x) - box.size_x / 2.0, 0.0)
    out_y = max(abs(local_y) - box.size_y / 2.0, 0.0)
    return math.hypot(out_x, out_y)


def distance_to_segment(px: float, py: float, a: tuple[float, float], b: tuple[float, float]) -> float:
    """Metres from (px, py) to the segment from ``a`` to ``b``."""
    ax, ay = a
    bx, by = b
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    f = 0.0 if length2 == 0.0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / length2))
    return math.hypot(px - (ax + f * dx), py - (ay + f * dy))
