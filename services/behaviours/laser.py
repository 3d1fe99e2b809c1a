"""Reading a LaserScan the way the behaviours need: the nearest return in a sector, the returns
as points, leg-sized clusters, and a straight wall fitted to a side.

All angles in the robot's frame: 0 straight ahead, counter-clockwise, degrees where a user
sets them. A range of 0.0 is no return (the Neato's convention) and is skipped everywhere.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shared_models.sensor_msgs import LaserScan

__all__ = ["Cluster", "Wall", "clusters", "fit_wall", "nearest_in_sector", "points"]


def _valid(scan: LaserScan, r: float) -> bool:
    return r > 0.0 and scan.range_min <= r <= scan.range_max


def nearest_in_sector(scan: LaserScan, centre_deg: float, half_width_deg: float) -> float:
    """The nearest return within ``half_width_deg`` of ``centre_deg``; inf when there is none."""
    best = math.inf
    centre = math.radians(centre_deg)
    half = math.radians(half_width_deg)
    for i, r in enumerate(scan.ranges):
        if not _valid(scan, r):
            continue
        angle = scan.angle_min + i * scan.angle_increment
        if abs(math.remainder(angle - centre, math.tau)) <= half and r < best:
            best = r
    return best


def points(scan: LaserScan, centre_deg: float = 0.0, half_width_deg: float = 180.0) -> list[tuple[float, float]]:
    """The returns within the sector as (x, y) points in the laser's frame."""
    centre = math.radians(centre_deg)
    half = math.radians(half_width_deg)
    found = []
    for i, r in enumerate(scan.ranges):
        angle = scan.angle_min + i * scan.angle_increment
        if _valid(scan, r) and abs(math.remainder(angle - centre, math.tau)) <= half:
            found.append((r * math.cos(angle), r * math.sin(angle)))
    return found


@dataclass(frozen=True, slots=True)
class Cluster:
    """Neighbouring returns that belong together: their centre (x, y), width (m, first to last
    return), how many returns, and whether it stands out in front of what the beams either side
    of it see (nothing, or something at least ``stand_out_m`` further): a leg in front of a wall
    does; a piece of wall seen at a grazing angle does not."""

    x: float
    y: float
    width: float
    count: int
    stands_out: bool

    @property
    def distance(self) -> float:
        return math.hypot(self.x, self.y)

    @property
    def bearing(self) -> float:
        return math.atan2(self.y, self.x)


def clusters(scan: LaserScan, gap_m: float = 0.1, stand_out_m: float = 0.2) -> list[Cluster]:
    """The returns split wherever two neighbouring beams' points are more than ``gap_m`` apart
    (or one has no return), in beam order; the scan's ends join (it is a full circle)."""
    ranges = scan.ranges
    n = len(ranges)

    def point(i: int) -> tuple[float, float]:
        angle = scan.angle_min + i * scan.angle_increment
        return ranges[i] * math.cos(angle), ranges[i] * math.sin(angle)

    runs: list[list[int]] = []
    run: list[int] = []
    for i, r in enumerate(ranges):
        if not _valid(scan, r):
            if run:
                runs.append(run)
            run = []
            continue
        if run and math.dist(point(i), point(run[-1])) > gap_m:
            runs.append(run)
            run = []
        run.append(i)
    if run:
        runs.append(run)
    full_circle = n * scan.angle_increment >= math.tau - 1e-6
    wraps = full_circle and len(runs) > 1 and runs[0][0] == 0 and runs[-1][-1] == n - 1
    if wraps and math.dist(point(0), point(n - 1)) <= gap_m:
        runs[0] = runs.pop() + runs[0]

    def stands_out(edge: int, neighbour: int) -> bool:
        if not 0 <= neighbour < n:
            if not full_circle:
                return True
            neighbour %= n
        r = ranges[neighbour]
        return not _valid(scan, r) or r >= ranges[edge] + stand_out_m

    found = []
    for indices in runs:
        xy = [point(i) for i in indices]
        found.append(
            Cluster(
                x=sum(x for x, _ in xy) / len(xy),
                y=sum(y for _, y in xy) / len(xy),
                width=math.dist(xy[0], xy[-1]),
                count=len(xy),
                stands_out=stands_out(indices[0], indices[0] - 1) and stands_out(indices[-1], indices[-1] + 1),
            )
        )
    return found


@dataclass(frozen=True, slots=True)
class Wall:
    """A straight wall fitted to returns: its perpendicular distance (m) from the laser and its
    direction relative to the heading (rad; 0 = parallel to the way the robot drives)."""

    distance: float
    angle: float


def fit_wall(found: list[tuple[float, float]]) -> Wall | None:
    """The least-squares line through ``found`` (at least 5 points), or None."""
    n = len(found)
    if n < 5:
        return None
    mx = sum(x for x, _ in found) / n
    my = sum(y for _, y in found) / n
    sxx = sum((x - mx) ** 2 for x, _ in found)
    syy = sum((y - my) ** 2 for _, y in found)
    sxy = sum((x - mx) * (y - my) for x, y in found)
    direction = 0.5 * math.atan2(2.0 * sxy, sxx - syy)  # the principal axis
    # The distance from the origin to the line through (mx, my) along ``direction``.
    distance = abs(-math.sin(direction) * mx + math.cos(direction) * my)
    angle = math.remainder(direction, math.pi)  # a line has no sense: within +-pi/2
    return Wall(distance, angle)
