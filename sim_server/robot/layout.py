"""The room's furniture and the person's walk: where things are, before any physics.

Pure geometry with a caller-owned :class:`random.Random`, so ``--seed`` fixes the room. The
obstacles keep clear of robot 1's corridor to the +x wall, of every robot start, of the
person's loop, of the walls (a lane to follow them) and of each other (room to pass between).
A class's robots (``skydeck class``) start on a grid clear of the person's loop
(:func:`class_starts`).
"""

from __future__ import annotations

import bisect
import math
import random
from collections.abc import Sequence
from dataclasses import dataclass

from sim_server.robot.limits import (
    CLASS_GRID_PITCHES_M,
    CLASS_PERSON_CLEARANCE_M,
    CORRIDOR_HALF_WIDTH_M,
    LEG_RADIUS_M,
    LEG_SPACING_M,
    OBSTACLE_GAP_M,
    OBSTACLE_SIZE_M,
    PERSON_LOOP_CENTRE_M,
    PERSON_LOOP_RADII_M,
    ROBOT_RADIUS_M,
    ROBOT_STARTS_M,
    ROOM_HALF_SIZE_M,
    WALL_LANE_M,
)

__all__ = ["Obstacle", "PersonLoop", "class_starts", "place_obstacles"]

_MAX_TRIES_PER_OBSTACLE = 500
_MAX_ATTEMPTS = 20
_LOOP_SEGMENTS = 720


@dataclass(frozen=True, slots=True)
class Obstacle:
    """A square box on the floor: centre, heading (rad) and side (m)."""

    x: float
    y: float
    yaw: float
    size: float

    @property
    def radius(self) -> float:
        """Half its diagonal: no part of it is further from its centre."""
        return self.size / math.sqrt(2.0)


class PersonLoop:
    """The person's walk: an ellipse, counter-clockwise, by distance walked.

    Example::

        loop = PersonLoop()
        x, y, heading = loop.at(12.5)     # after 12.5 m of walking
    """

    def __init__(
        self,
        centre: tuple[float, float] = PERSON_LOOP_CENTRE_M,
        radii: tuple[float, float] = PERSON_LOOP_RADII_M,
    ) -> None:
        cx, cy = centre
        a, b = radii
        self.points = [
            (cx + a * math.cos(t), cy + b * math.sin(t))
            for t in (math.tau * i / _LOOP_SEGMENTS for i in range(_LOOP_SEGMENTS + 1))
        ]
        self._lengths = [0.0]
        for (x0, y0), (x1, y1) in zip(self.points, self.points[1:], strict=False):
            self._lengths.append(self._lengths[-1] + math.hypot(x1 - x0, y1 - y0))
        self.length_m = self._lengths[-1]

    def at(self, distance_m: float) -> tuple[float, float, float]:
        """Position (x, y) and heading after walking ``distance_m`` from the start (the loop's
        point furthest along +x)."""
        s = distance_m % self.length_m
        i = min(bisect.bisect_right(self._lengths, s), len(self._lengths) - 1)
        s0, s1 = self._lengths[i - 1], self._lengths[i]
        (x0, y0), (x1, y1) = self.points[i - 1], self.points[i]
        f = (s - s0) / (s1 - s0) if s1 > s0 else 0.0
        return x0 + f * (x1 - x0), y0 + f * (y1 - y0), math.atan2(y1 - y0, x1 - x0)

    def distance_to(self, x: float, y: float) -> float:
        """Least distance from (x, y) to the path (to within a centimetre)."""
        return min(math.hypot(x - px, y - py) for px, py in self.points)


def class_starts(count: int, loop: PersonLoop) -> list[tuple[float, float]]:
    """Where a class's ``count`` robots start: on the widest grid of CLASS_GRID_PITCHES_M (centred
    in the room, a pitch's half from the walls at least) that has ``count`` points clear of the
    person's walk, row by row from the front (+x). ValueError when none has room."""
    for pitch in CLASS_GRID_PITCHES_M:
        per_side = int((2.0 * ROOM_HALF_SIZE_M) / pitch)  # a half pitch to each wall at least
        first = -(per_side - 1) * pitch / 2.0
        cells = [round(first + i * pitch, 3) for i in range(per_side)]
        free = [
            (x, y)
            for x in reversed(cells)
            for y in reversed(cells)
            if loop.distance_to(x, y) >= CLASS_PERSON_CLEARANCE_M
        ]
        if len(free) >= count:
            return _spread(free, count)
    raise ValueError(f"{count} robots do not fit in the room apart")


def _spread(cells: list[tuple[float, float]], count: int) -> list[tuple[float, float]]:
    """``count`` of ``cells`` (in order), evenly spaced along them: a small class spreads over
    the whole grid rather than filling its first rows."""
    step = len(cells) / count
    return [cells[int(i * step)] for i in range(count)]


def place_obstacles(
    rng: random.Random, count: int, loop: PersonLoop, starts: Sequence[tuple[float, float]] = ROBOT_STARTS_M
) -> list[Obstacle]:
    """Draw ``count`` box obstacles: uniform in the room's inner square, each drawn again until
    it keeps its distances (see the module's docstring); a set that gets stuck (no room left
    for the next box) is drawn again from the start.

    Raises ValueError when they cannot be placed (far more than the room holds).
    """
    for _attempt in range(_MAX_ATTEMPTS):
        placed = _try_to_place(rng, count, loop, starts)
        if placed is not None:
            return placed
    raise ValueError(f"cannot place {count} obstacles apart in the room; use fewer")


def _try_to_place(
    rng: random.Random, count: int, loop: PersonLoop, starts: Sequence[tuple[float, float]]
) -> list[Obstacle] | None:
    placed: list[Obstacle] = []
    inner = ROOM_HALF_SIZE_M - WALL_LANE_M
    robot_room = ROBOT_RADIUS_M + OBSTACLE_GAP_M
    person_room = LEG_SPACING_M / 2.0 + LEG_RADIUS_M + OBSTACLE_GAP_M
    corridor_x = ROBOT_STARTS_M[0][0] - ROBOT_RADIUS_M
    for _ in range(count):
        for _try in range(_MAX_TRIES_PER_OBSTACLE):
            size = rng.uniform(*OBSTACLE_SIZE_M)
            reach = size / math.sqrt(2.0)  # turned by up to 45 degrees, it reaches this far
            candidate = Obstacle(
                x=rng.uniform(-inner + reach, inner - reach),
                y=rng.uniform(-inner + reach, inner - reach),
                yaw=rng.uniform(-math.pi / 4.0, math.pi / 4.0),
                size=size,
            )
            r = candidate.radius
            if candidate.x + r > corridor_x and abs(candidate.y) - r < CORRIDOR_HALF_WIDTH_M:
                continue
            if any(math.hypot(candidate.x - sx, candidate.y - sy) < r + robot_room for sx, sy in starts):
                continue
            if loop.distance_to(candidate.x, candidate.y) < r + person_room:
                continue
            if any(
                math.hypot(candidate.x - o.x, candidate.y - o.y) < r + o.radius + OBSTACLE_GAP_M
                for o in placed
            ):
                continue
            placed.append(candidate)
            break
        else:
            return None
    return placed
