"""Where the AI lands once every box is visited, and what that last leg costs the tour.

Two policies (``skydeck run ai --landing ...``, ``SKYDECK_AI_LANDING``):

- ``beside_last_box`` (the default): land at the nearest clear spot beside the last box. Boxes
  are 2 m tall, so the drone cannot set down over one; the spot keeps ``CLEARANCE_M`` from every
  box centre (a box's footprint at any yaw, the drone's rotors and a margin for where the drone
  actually touches down) and stays inside the arena. Of the spots at the least clear distance,
  the one straight ahead of the drone's arrival is taken, so it flies on without turning back.
- ``home``: fly back to the start and land there (the tour is then planned closed).

The finishing leg of each box, the distance from it to where the drone would land after it,
feeds the planner (``plan_tour(..., finish=...)``), so the whole flight, take-off to touchdown,
is what the tour minimises.

    >>> spot = landing_spot((10.0, 0.0), [(10.0, 0.0)], arriving_from=(0.0, 0.0))
    >>> round(spot[0] - 10.0, 2), spot[1]
    (2.31, 0.0)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Literal, get_args

from sim_server.drone.limits import ARENA_HALF_SIZE_M, BOX_SIZE_M

__all__ = [
    "CLEARANCE_M",
    "DEFAULT_LANDING",
    "LANDING_POLICIES",
    "LandingPolicy",
    "finishing_legs",
    "is_clear",
    "landing_spot",
]

LandingPolicy = Literal["beside_last_box", "home"]
LANDING_POLICIES: tuple[str, ...] = get_args(LandingPolicy)
DEFAULT_LANDING: LandingPolicy = "beside_last_box"

BOX_FOOTPRINT_RADIUS_M = BOX_SIZE_M / 2.0 * math.sqrt(2.0)
"""A box at rest stands on a face: its footprint, at any yaw, lies within this of its centre."""
DRONE_RADIUS_M = 0.4
"""The Iris's 0.25 m arms plus a 10-inch propeller's radius."""
LANDING_MARGIN_M = 0.5
"""Room for where the drone touches down: it lands where it is once within 0.1 m of the spot,
and may drift a little on the way down."""
CLEARANCE_M = BOX_FOOTPRINT_RADIUS_M + DRONE_RADIUS_M + LANDING_MARGIN_M
"""Least distance from a landing spot to any box centre (2.31 m)."""

# The search: rings of candidate spots around the last box, from CLEARANCE_M outwards.
_DIRECTIONS = 72  # every 5 degrees
_RING_STEP_M = 0.25
_MAX_RING_M = 12.0

Point2 = tuple[float, float]


def is_clear(spot: Point2, boxes: Sequence[Point2]) -> bool:
    """Whether the drone may land at ``spot``: inside the arena, CLEARANCE_M from every box."""
    x, y = spot
    if abs(x) > ARENA_HALF_SIZE_M or abs(y) > ARENA_HALF_SIZE_M:
        return False
    return all(math.dist(spot, box) >= CLEARANCE_M - 1e-9 for box in boxes)


def landing_spot(last: Point2, boxes: Sequence[Point2], *, arriving_from: Point2) -> Point2 | None:
    """The nearest clear spot beside box ``last``, straight ahead of the arrival if it can be.

    ``arriving_from`` is where the drone comes from (the previous box, or the drone itself).
    None when no clear spot lies within reach of the box (a box hemmed in by others and the
    arena's edge); the caller then lands at home.
    """
    heading = math.atan2(last[1] - arriving_from[1], last[0] - arriving_from[0])
    # One fixed set of directions, tried in the order of how far they turn from the heading
    # (straight on first): the nearest clear ring is then the same whichever way the drone comes.
    angles = sorted(
        (math.tau * k / _DIRECTIONS for k in range(_DIRECTIONS)),
        key=lambda angle: abs(math.remainder(angle - heading, math.tau)),
    )
    radius = CLEARANCE_M
    while radius <= _MAX_RING_M:
        for angle in angles:
            spot = (last[0] + radius * math.cos(angle), last[1] + radius * math.sin(angle))
            if is_clear(spot, boxes):
                return spot
        radius += _RING_STEP_M
    return None


def finishing_legs(policy: LandingPolicy, boxes: Sequence[Point2], *, home: Point2) -> list[float]:
    """For each box, how far the drone flies after it to land, were it the tour's last.

    Beside a box the leg is the least clear distance around it (the same whichever way the drone
    arrives); at home, the distance back to the start.
    """
    if policy == "home":
        return [math.dist(box, home) for box in boxes]
    legs = []
    for box in boxes:
        spot = landing_spot(box, boxes, arriving_from=box)
        legs.append(math.dist(box, home) if spot is None else math.dist(box, spot))
    return legs
