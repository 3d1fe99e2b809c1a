"""``estop``: drive ahead and stop before the wall (or whatever is ahead), and stay stopped.

- ``estop.travel_m``: how far the robot drove (it must not stop at once);
- ``estop.clearance_m``: the gap between its body and the nearest wall or obstacle at the end;
- ``estop.moved_after_stop_m``: how far it moved after it first came to rest (once it had
  driven ``min_travel_m``): a stop is for good;
- ``estop.bumps``: contacts of the bumper (the laser should have stopped it first).
"""

from __future__ import annotations

import math

from pydantic import Field

from services.grading.criteria.base import (
    CriterionSpec,
    Figure,
    Mark,
    NoOptions,
    Options,
    bumps_spec,
)
from services.grading.criteria.robot_common import gap, start_of
from services.grading.geometry import path_length
from services.grading.tracks import Tracks

__all__ = ["CRITERIA", "StopOptions"]


class StopOptions(Options):
    min_travel_m: float = Field(default=0.5, ge=0)
    """Coming to rest before this counts as not having set off yet."""
    rest_speed: float = Field(default=0.02, gt=0)
    """Below this speed (m/s) the robot is at rest."""
    rest_s: float = Field(default=1.0, gt=0)
    """...for at least this long."""


def travel(tracks: Tracks, _: NoOptions) -> Figure:
    start_of(tracks.robot)
    metres = path_length(tracks.robot)
    return Figure(metres, f"drove {metres:.2f} m")


def clearance(tracks: Tracks, _: NoOptions) -> Figure:
    start_of(tracks.robot)
    end = tracks.robot[-1]
    metres = gap(end, tracks.obstacles)
    mark = Mark(end.x, end.y, f"end: {metres:.2f} m clear")
    return Figure(metres, f"ended {metres:.3f} m short of the nearest surface", (mark,))


def moved_after_stop(tracks: Tracks, options: StopOptions) -> Figure:
    track = tracks.robot
    start = start_of(track)
    rest_from: int | None = None  # index of the first pose of the current rest
    stop: int | None = None
    for i in range(1, len(track)):
        a, b = track[i - 1], track[i]
        away = math.hypot(b.x - start.x, b.y - start.y)
        speed = math.hypot(b.x - a.x, b.y - a.y) / (b.t - a.t) if b.t > a.t else 0.0
        if away < options.min_travel_m or speed >= options.rest_speed:
            rest_from = None
            continue
        rest_from = i - 1 if rest_from is None else rest_from
        if b.t - track[rest_from].t >= options.rest_s:
            stop = rest_from
            break
    if stop is None:
        return Figure(math.inf, "never came to rest")
    stopped = track[stop]
    moved = max(math.hypot(p.x - stopped.x, p.y - stopped.y) for p in track[stop:])
    mark = Mark(stopped.x, stopped.y, f"rest at {stopped.t:.1f} s")
    return Figure(moved, f"came to rest at {stopped.t:.1f} s, then moved {moved:.3f} m", (mark,))


CRITERIA = [
    CriterionSpec("estop.travel_m", "robot", "m", "how far the robot drove", NoOptions, travel),
    CriterionSpec("estop.clearance_m", "robot", "m", "gap to the nearest wall or obstacle at the end", NoOptions, clearance),
    CriterionSpec("estop.moved_after_stop_m", "robot", "m", "how far the robot moved once it had stopped", StopOptions, moved_after_stop),
    bumps_spec("estop"),
]
