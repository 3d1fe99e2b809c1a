"""``obstacle_avoider``: drive to a goal (in the start's frame, as the node's ``goal_x``,
``goal_y``) around the obstacles.

- ``obstacle_avoider.goal_error_m``: how far from the goal the robot ended;
- ``obstacle_avoider.progress``: the share of the way from the start to the goal it covered
  (1 at the goal, 0 where it started or further);
- ``obstacle_avoider.bumps``: contacts of the bumper.
"""

from __future__ import annotations

import math

from pydantic import Field

from services.grading.criteria.base import CriterionSpec, Figure, Mark, Options, bumps_spec
from services.grading.criteria.robot_common import start_of
from services.grading.tracks import Tracks

__all__ = ["CRITERIA", "GoalOptions", "goal_in_world"]


class GoalOptions(Options):
    goal_x: float = Field(default=2.6, ge=-8.0, le=8.0)
    goal_y: float = Field(default=1.35, ge=-8.0, le=8.0)


def goal_in_world(tracks: Tracks, options: GoalOptions) -> tuple[float, float]:
    """The goal, given in the start's frame (odom), on the map."""
    start = start_of(tracks.robot)
    c, s = math.cos(start.yaw), math.sin(start.yaw)
    return start.x + c * options.goal_x - s * options.goal_y, start.y + s * options.goal_x + c * options.goal_y


def goal_error(tracks: Tracks, options: GoalOptions) -> Figure:
    gx, gy = goal_in_world(tracks, options)
    end = tracks.robot[-1]
    error = math.hypot(gx - end.x, gy - end.y)
    return Figure(error, f"ended {error:.3f} m from the goal", (Mark(gx, gy, "goal", "target"),))


def progress(tracks: Tracks, options: GoalOptions) -> Figure:
    gx, gy = goal_in_world(tracks, options)
    start, end = start_of(tracks.robot), tracks.robot[-1]
    whole = math.hypot(gx - start.x, gy - start.y)
    if whole == 0.0:
        raise ValueError("the goal is where the robot starts")
    share = max(0.0, 1.0 - math.hypot(gx - end.x, gy - end.y) / whole)
    return Figure(share, f"covered {share:.0%} of the {whole:.2f} m to the goal")


CRITERIA = [
    CriterionSpec("obstacle_avoider.goal_error_m", "robot", "m", "distance from the goal at the end", GoalOptions, goal_error),
    CriterionSpec("obstacle_avoider.progress", "robot", "", "share of the way to the goal covered", GoalOptions, progress),
    bumps_spec("obstacle_avoider"),
]
