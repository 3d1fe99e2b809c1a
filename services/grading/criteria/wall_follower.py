"""``wall_follower``: find a wall and follow it at ``distance``, the wall on one ``side``.

Measured on the room's walls (not the obstacles), from the robot's centre, from the moment the
robot first came within the band (it starts in the middle of the room and must drive to a wall):

- ``wall_follower.time_to_wall_s``: when it first came within the band;
- ``wall_follower.band_fraction``: the share of the time since then that it stayed within
  ``distance`` ± ``tolerance`` of a wall on its ``side`` (the wall's bearing within 60° of
  square to the robot: a wall ahead is on no side);
- ``wall_follower.followed_m``: how far it drove within the band (a robot that parks by the
  wall stays within it, but follows nothing);
- ``wall_follower.bumps``: contacts of the bumper.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from pydantic import Field

from services.grading.criteria.base import CriterionSpec, Figure, Mark, Options, bumps_spec
from services.grading.criteria.robot_common import nearest_wall, start_of
from services.grading.shapes import Box, Pose
from services.grading.tracks import Tracks

__all__ = ["CRITERIA", "Band", "BandOptions", "in_band"]


# The nearest wall is on a side when its bearing is within 60 degrees of square to the robot:
# a robot driving at a wall has it ahead, whichever way it drifts.
_SIDE_FROM, _SIDE_TO = math.radians(30.0), math.radians(150.0)


class BandOptions(Options):
    distance: float = Field(default=0.5, gt=0, le=3.0)
    tolerance: float = Field(default=0.15, gt=0, le=2.0)
    side: Literal["left", "right", "either"] = "right"


@dataclass(frozen=True)
class Band:
    """Where a run was within the band: per pose, in or out; from the first pose in."""

    inside: list[bool]
    first: int | None
    """The index of the first pose within the band (None: never)."""


def in_band(track: Sequence[Pose], walls: Sequence[Box], options: BandOptions) -> Band:
    """Each pose of ``track``: within ``distance`` ± ``tolerance`` of a wall on ``side``?"""
    if not walls:
        raise ValueError("the run recorded no walls (/simulator/obstacles)")
    inside = []
    for pose in track:
        distance, bearing = nearest_wall(pose, walls)
        beside = _SIDE_FROM <= abs(bearing) <= _SIDE_TO  # a wall dead ahead (or behind) is on no side
        on_side = beside and (options.side == "either" or (bearing < 0.0) == (options.side == "right"))
        inside.append(on_side and abs(distance - options.distance) <= options.tolerance)
    first = next((i for i, ok in enumerate(inside) if ok), None)
    return Band(inside, first)


def time_to_wall(tracks: Tracks, options: BandOptions) -> Figure:
    start = start_of(tracks.robot)
    band = in_band(tracks.robot, tracks.walls, options)
    if band.first is None:
        return Figure(math.inf, "never came within the band")
    pose = tracks.robot[band.first]
    return Figure(pose.t - start.t, f"within the band at {pose.t:.1f} s", (Mark(pose.x, pose.y, "in the band"),))


def band_fraction(tracks: Tracks, options: BandOptions) -> Figure:
    start_of(tracks.robot)
    band = in_band(tracks.robot, tracks.walls, options)
    if band.first is None:
        return Figure(0.0, "never came within the band")
    since = band.inside[band.first :]
    share = sum(since) / len(since)
    misses = tuple(
        Mark(pose.x, pose.y, f"out of the band at {pose.t:.1f} s", "miss")
        for pose, ok in zip(tracks.robot[band.first :: 5], since[::5], strict=False)
        if not ok
    )
    return Figure(share, f"{share:.0%} of {tracks.robot[-1].t - tracks.robot[band.first].t:.0f} s within the band", misses)


def followed(tracks: Tracks, options: BandOptions) -> Figure:
    start_of(tracks.robot)
    band = in_band(tracks.robot, tracks.walls, options)
    track = tracks.robot
    metres = math.fsum(
        math.hypot(b.x - a.x, b.y - a.y)
        for a, b, ok_a, ok_b in zip(track, track[1:], band.inside, band.inside[1:], strict=False)
        if ok_a and ok_b
    )
    return Figure(metres, f"drove {metres:.2f} m within the band")


CRITERIA = [
    CriterionSpec("wall_follower.time_to_wall_s", "robot", "s", "when the robot first came within the band", BandOptions, time_to_wall),
    CriterionSpec("wall_follower.band_fraction", "robot", "", "share of the time within the band, since it first was", BandOptions, band_fraction),
    CriterionSpec("wall_follower.followed_m", "robot", "m", "distance driven within the band", BandOptions, followed),
    bumps_spec("wall_follower"),
]
