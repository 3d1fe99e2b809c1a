"""Made-up runs for the criteria's tests: a room like the robot world's, and tracks along paths."""

from __future__ import annotations

import math
from collections.abc import Callable

from services.grading.shapes import Box, BumpEvent, Pose
from services.grading.tracks import Tracks

HALF = 4.0
THICK = 0.1


def room(*obstacles: Box) -> list[Box]:
    """The robot world's four walls (inner faces at +-4 m), and ``obstacles``."""
    length = 2 * (HALF + THICK)
    return [
        Box(HALF + THICK / 2, 0.0, THICK, length, 0.0, "wall"),
        Box(-HALF - THICK / 2, 0.0, THICK, length, 0.0, "wall"),
        Box(0.0, HALF + THICK / 2, length, THICK, 0.0, "wall"),
        Box(0.0, -HALF - THICK / 2, length, THICK, 0.0, "wall"),
        *obstacles,
    ]


def along(path: Callable[[float], tuple[float, float]], duration_s: float, hz: float = 10.0) -> list[Pose]:
    """Poses at ``hz`` along ``path(t) -> (x, y)``, heading along the motion."""
    poses = []
    steps = round(duration_s * hz)
    for i in range(steps + 1):
        t = i / hz
        x, y = path(t)
        nx, ny = path(t + 1e-3)
        yaw = math.atan2(ny - y, nx - x) if (nx, ny) != (x, y) else (poses[-1].yaw if poses else 0.0)
        poses.append(Pose(t, x, y, yaw))
    return poses


def polyline(points: list[tuple[float, float]], speed: float) -> Callable[[float], tuple[float, float]]:
    """A path through ``points`` at ``speed`` m/s, resting at the last one."""
    legs = []
    for a, b in zip(points, points[1:], strict=False):
        legs.append((a, b, math.hypot(b[0] - a[0], b[1] - a[1])))

    def at(t: float) -> tuple[float, float]:
        left = t * speed
        for (ax, ay), (bx, by), length in legs:
            if left <= length and length > 0:
                f = left / length
                return ax + f * (bx - ax), ay + f * (by - ay)
            left -= length
        return points[-1]

    return at


def run(robot: list[Pose], *, obstacles: list[Box] | None = None, **fields: object) -> Tracks:
    tracks = Tracks(world="robot", seed=1, robot=robot, obstacles=room() if obstacles is None else obstacles)
    for name, value in fields.items():
        setattr(tracks, name, value)
    tracks.end_s = robot[-1].t if robot else 0.0
    return tracks


def bump(t: float, x: float = 0.0, y: float = 0.0) -> BumpEvent:
    return BumpEvent(t, x, y, ("left_front",))
