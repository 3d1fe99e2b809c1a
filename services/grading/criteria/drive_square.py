"""``drive_square``: one square of ``side`` metres from where the robot starts, turning left (or
right), and back to the start.

- ``drive_square.corner_error_m``: the worst of the three far corners, each by how close the
  robot's path came to where it should be (the square laid on the start pose);
- ``drive_square.closure_m``: how far from its start the robot ended.
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field

from services.grading.criteria.base import CriterionSpec, Figure, Mark, Options
from services.grading.criteria.robot_common import start_of
from services.grading.geometry import distance_to_segment
from services.grading.tracks import Tracks

__all__ = ["CRITERIA", "SquareOptions", "square_corners"]


class SquareOptions(Options):
    side: float = Field(default=1.0, gt=0, le=6.0)
    turn: Literal["left", "right"] = "left"


def square_corners(tracks: Tracks, options: SquareOptions) -> list[tuple[float, float]]:
    """The square's corners after the start, in driving order: three far ones, then the start."""
    start = start_of(tracks.robot)
    side, sign = options.side, (1.0 if options.turn == "left" else -1.0)
    c, s = math.cos(start.yaw), math.sin(start.yaw)
    corners = []
    for along, across in ((1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)):
        lx, ly = side * along, sign * side * across
        corners.append((start.x + c * lx - s * ly, start.y + s * lx + c * ly))
    return corners


def corner_error(tracks: Tracks, options: SquareOptions) -> Figure:
    corners = square_corners(tracks, options)[:3]
    points = [(pose.x, pose.y) for pose in tracks.robot]
    segments = list(zip(points, points[1:], strict=False)) or [(points[0], points[0])]
    errors = [min(distance_to_segment(cx, cy, a, b) for a, b in segments) for cx, cy in corners]
    worst = max(range(3), key=lambda i: errors[i])
    marks = tuple(Mark(x, y, f"corner {i + 1}: {errors[i]:.2f} m", "target") for i, (x, y) in enumerate(corners))
    return Figure(errors[worst], f"corner {worst + 1} missed by {errors[worst]:.3f} m", marks)


def closure(tracks: Tracks, options: SquareOptions) -> Figure:
    start, end = start_of(tracks.robot), tracks.robot[-1]
    distance = math.hypot(end.x - start.x, end.y - start.y)
    return Figure(distance, f"ended {distance:.3f} m from the start", (Mark(start.x, start.y, "start", "target"),))


CRITERIA = [
    CriterionSpec("drive_square.corner_error_m", "robot", "m", "how far the path passed from the worst corner", SquareOptions, corner_error),
    CriterionSpec("drive_square.closure_m", "robot", "m", "how far from its start the robot ended", SquareOptions, closure),
]
