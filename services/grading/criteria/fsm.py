"""``fsm``: a finite-state controller that drives squares until something is near ahead, then
follows the wall; it says its state on ``fsm/state`` (std_msgs/String), ``drive_square`` then
``follow_wall``.

- ``fsm.switched``: 1 if the state went from ``square_state`` to ``wall_state``, else 0;
- ``fsm.switch_clearance_m``: the gap between the robot's body and the nearest surface when it
  switched (it must switch before it touches anything);
- ``fsm.wall_band_fraction``: after the switch, the share of the time within the wall band
  (as ``wall_follower.band_fraction``);
- ``fsm.bumps``: contacts of the bumper.
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field

from services.grading.criteria.base import CriterionSpec, Figure, Mark, Options, bumps_spec
from services.grading.criteria.robot_common import gap, start_of
from services.grading.criteria.wall_follower import BandOptions, in_band
from services.grading.geometry import position_at
from services.grading.shapes import Pose
from services.grading.tracks import Tracks

__all__ = ["CRITERIA", "FsmOptions", "switch_time"]


class FsmOptions(Options):
    square_state: str = "drive_square"
    wall_state: str = "follow_wall"
    distance: float = Field(default=0.5, gt=0, le=3.0)
    tolerance: float = Field(default=0.15, gt=0, le=2.0)
    side: Literal["left", "right", "either"] = "right"


def switch_time(tracks: Tracks, options: FsmOptions) -> float | None:
    """When the state first went from the square's to the wall's (None: it never did)."""
    seen_square = False
    for t, state in tracks.states:
        if state == options.square_state:
            seen_square = True
        elif state == options.wall_state and seen_square:
            return t
    return None


def switched(tracks: Tracks, options: FsmOptions) -> Figure:
    t = switch_time(tracks, options)
    states = " -> ".join(state for _, state in tracks.states) or "no state published on /fsm/state"
    return Figure(0.0 if t is None else 1.0, states)


def switch_clearance(tracks: Tracks, options: FsmOptions) -> Figure:
    start_of(tracks.robot)
    t = switch_time(tracks, options)
    if t is None:
        return Figure(-math.inf, "never switched")
    x, y = position_at(tracks.robot, t)
    metres = gap(Pose(t, x, y), tracks.obstacles)
    return Figure(metres, f"switched at {t:.1f} s, {metres:.2f} m clear", (Mark(x, y, f"switch at {t:.1f} s"),))


def wall_band_fraction(tracks: Tracks, options: FsmOptions) -> Figure:
    start_of(tracks.robot)
    t = switch_time(tracks, options)
    if t is None:
        return Figure(0.0, "never switched to following the wall")
    after = [pose for pose in tracks.robot if pose.t >= t]
    band = in_band(after, tracks.walls, BandOptions(distance=options.distance, tolerance=options.tolerance, side=options.side))
    if band.first is None:
        return Figure(0.0, "never came within the band after the switch")
    since = band.inside[band.first :]
    share = sum(since) / len(since)
    return Figure(share, f"{share:.0%} of the time within the band after the switch")


CRITERIA = [
    CriterionSpec("fsm.switched", "robot", "", "whether the state went from the square to the wall", FsmOptions, switched),
    CriterionSpec("fsm.switch_clearance_m", "robot", "m", "gap to the nearest surface when it switched", FsmOptions, switch_clearance),
    CriterionSpec("fsm.wall_band_fraction", "robot", "", "share of the time within the wall band after the switch", FsmOptions, wall_band_fraction),
    bumps_spec("fsm"),
]
