"""``drone_mission``: fly over every box (the drone workshop's AI).

- ``drone_mission.boxes_visited``: the share of the boxes the drone passed over, within
  ``visit_radius_m`` of the box's centre and at least ``min_altitude_m`` up;
- ``drone_mission.path_ratio``: the horizontal path flown from the start until the last box
  was visited, against the shortest tour from the start over every box (the AI's planner,
  ``services.ai.planner``): 1.0 is the best there is; infinite when a box was missed.
"""

from __future__ import annotations

import math

from pydantic import Field

from services.ai.planner import plan_tour
from services.grading.criteria.base import CriterionSpec, Figure, Mark, Options
from services.grading.geometry import path_length
from services.grading.tracks import Tracks

__all__ = ["CRITERIA", "VisitOptions", "visits"]


class VisitOptions(Options):
    visit_radius_m: float = Field(default=0.5, gt=0, le=5.0)
    min_altitude_m: float = Field(default=2.2, ge=0)


def visits(tracks: Tracks, options: VisitOptions) -> list[float | None]:
    """When the drone first passed over each box (None: never)."""
    if not tracks.drone:
        raise ValueError("the run recorded no drone pose (/drone/pose)")
    if not tracks.boxes:
        raise ValueError("the run recorded no boxes (/simulator/boxes)")
    first: list[float | None] = [None] * len(tracks.boxes)
    for pose in tracks.drone:
        if pose.z < options.min_altitude_m:
            continue
        for i, box in enumerate(tracks.boxes):
            if first[i] is None and math.hypot(pose.x - box.x, pose.y - box.y) <= options.visit_radius_m:
                first[i] = pose.t
    return first


def boxes_visited(tracks: Tracks, options: VisitOptions) -> Figure:
    first = visits(tracks, options)
    done = sum(t is not None for t in first)
    marks = tuple(
        Mark(box.x, box.y, f"box {i + 1}: " + ("missed" if t is None else f"{t:.1f} s"), "miss" if t is None else "target")
        for i, (box, t) in enumerate(zip(tracks.boxes, first, strict=True))
    )
    return Figure(done / len(first), f"{done} of {len(first)} boxes", marks)


def path_ratio(tracks: Tracks, options: VisitOptions) -> Figure:
    first = visits(tracks, options)
    if any(t is None for t in first):
        return Figure(math.inf, "a box was missed")
    last = max(t for t in first if t is not None)
    start = tracks.drone[0]
    flown = path_length(tracks.drone, end_s=last)
    best = plan_tour((start.x, start.y), [(box.x, box.y) for box in tracks.boxes]).length_m
    if best <= 0.0:
        raise ValueError("the boxes are where the drone starts")
    return Figure(flown / best, f"flew {flown:.1f} m to the last box; the shortest tour is {best:.1f} m")


CRITERIA = [
    CriterionSpec("drone_mission.boxes_visited", "drone", "", "share of the boxes flown over", VisitOptions, boxes_visited),
    CriterionSpec("drone_mission.path_ratio", "drone", "", "path flown against the shortest tour", VisitOptions, path_ratio),
]
