"""``person_follower``: follow the walking person, keeping ``distance`` from them.

- ``person_follower.gap_band_fraction``: the share of the time after ``warmup_s`` (to catch up)
  that the robot's centre was within ``distance`` ± ``tolerance`` of the person's (between the
  legs);
- ``person_follower.bumps``: contacts of the bumper (the person's legs count).
"""

from __future__ import annotations

import math

from pydantic import Field

from services.grading.criteria.base import CriterionSpec, Figure, Mark, Options, bumps_spec
from services.grading.criteria.robot_common import start_of
from services.grading.tracks import Tracks

__all__ = ["CRITERIA", "GapOptions", "gaps"]


class GapOptions(Options):
    distance: float = Field(default=0.8, gt=0, le=4.0)
    tolerance: float = Field(default=0.4, gt=0, le=4.0)
    warmup_s: float = Field(default=10.0, ge=0)


def gaps(tracks: Tracks) -> list[tuple[float, float, float, float]]:
    """(t, gap m, robot x, robot y) at every time both the robot and the person were recorded."""
    start_of(tracks.robot)
    if not tracks.people:
        raise ValueError("the run recorded no person (/simulator/people)")
    people = {pose.t: pose for pose in tracks.people}
    return [
        (robot.t, math.hypot(person.x - robot.x, person.y - robot.y), robot.x, robot.y)
        for robot in tracks.robot
        if (person := people.get(robot.t)) is not None
    ]


def gap_band_fraction(tracks: Tracks, options: GapOptions) -> Figure:
    start_t = start_of(tracks.robot).t
    counted = [g for g in gaps(tracks) if g[0] - start_t >= options.warmup_s]
    if not counted:
        raise ValueError(f"the run is not longer than the warm-up ({options.warmup_s:g} s)")
    low, high = options.distance - options.tolerance, options.distance + options.tolerance
    inside = [low <= gap <= high for _, gap, _, _ in counted]
    share = sum(inside) / len(inside)
    misses = tuple(
        Mark(x, y, f"{gap:.2f} m from the person at {t:.1f} s", "miss")
        for (t, gap, x, y), ok in zip(counted[::5], inside[::5], strict=False)
        if not ok
    )
    mean = sum(g for _, g, _, _ in counted) / len(counted)
    return Figure(share, f"{share:.0%} of the time within {low:.2f}-{high:.2f} m (mean gap {mean:.2f} m)", misses)


CRITERIA = [
    CriterionSpec(
        "person_follower.gap_band_fraction", "robot", "", "share of the time at the right distance from the person",
        GapOptions, gap_band_fraction,
    ),  # fmt: skip
    bumps_spec("person_follower"),
]
