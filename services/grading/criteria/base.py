"""What a criterion is: a named figure measured on a recorded run, with its options.

Each family of criteria (one behaviour) is a module of this package listing its
:class:`CriterionSpec` s; an assignment names them (``wall_follower.band_fraction``), gives their
options (``params``, checked by the spec's model) and a threshold (``min`` or ``max``). Measures
are pure functions of :class:`~services.grading.tracks.Tracks`, so they are tested on tracks
made up in the test, without a world.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel, ConfigDict

from services.grading.shapes import BumpEvent
from services.grading.tracks import Tracks

__all__ = ["CriterionSpec", "Figure", "Mark", "NoOptions", "Options", "bump_events", "bumps_figure", "bumps_spec"]

_SAME_CONTACT_S = 0.2
"""Bump messages closer together than this are one contact (a bumper held for a while)."""


class Options(BaseModel):
    """A criterion's options: every field has a default; anything else is an error."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class NoOptions(Options):
    pass


@dataclass(frozen=True, slots=True)
class Mark:
    """A point the report draws on the map: what a figure was measured at."""

    x: float
    y: float
    label: str
    kind: str = "note"
    """``note``, ``target`` (where the robot should have been), ``bump``, ``miss``."""


@dataclass(frozen=True, slots=True)
class Figure:
    """What a criterion measured: its value, a phrase saying what it is, points on the map."""

    value: float
    detail: str = ""
    marks: tuple[Mark, ...] = ()


@dataclass(frozen=True, slots=True)
class CriterionSpec:
    """One criterion: ``family.figure``, the world it scores, its unit, its options and measure."""

    name: str
    world: str
    unit: str
    summary: str
    params: type[Options]
    measure: Callable[[Tracks, Any], Figure]

    def run(self, tracks: Tracks, params: Options) -> Figure:
        """The figure on ``tracks``; NaN when the run lacks what the criterion reads."""
        try:
            return self.measure(tracks, params)
        except ValueError as error:  # an empty track, a run that never started
            return Figure(math.nan, f"not measured: {error}")


def bump_events(bumps: Sequence[BumpEvent]) -> list[BumpEvent]:
    """The contacts: the first bump message of each run of messages close together in time."""
    events: list[BumpEvent] = []
    last_t = -math.inf
    for bump in bumps:
        if bump.t - last_t > _SAME_CONTACT_S:
            events.append(bump)
        last_t = bump.t
    return events


def bumps_figure(tracks: Tracks, _: Options) -> Figure:
    """How many times the robot's bumper touched something (a contact held counts once)."""
    events = bump_events(tracks.bumps)
    marks = tuple(Mark(e.x, e.y, f"bump {e.t:.1f} s", "bump") for e in events)
    detail = ", ".join(f"{e.t:.1f} s ({'/'.join(e.parts)})" for e in events[:5]) or "no contact"
    return Figure(float(len(events)), detail, marks)


def bumps_spec(family: str) -> CriterionSpec:
    """``FAMILY.bumps``: contacts of the bumper (walls, obstacles, the person)."""
    return CriterionSpec(
        f"{family}.bumps", "robot", "", "times the bumper touched something", NoOptions, bumps_figure
    )
