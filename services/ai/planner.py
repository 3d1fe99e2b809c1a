"""The AI's tour: visit every box once, starting from the drone, in the shortest order found.

The flight is what must be short, so a tour may end with a *finishing leg* whose length depends
on the point it leaves from: ``finish[j]`` metres after the last point ``j`` (to a landing spot
beside it, or back home for a closed tour). Without ``finish`` the tour is open (it ends at the
last point). Up to ``EXACT_LIMIT`` points the tour is optimal (Held-Karp dynamic programming over
subsets, O(n^2 2^n)); beyond that it is a nearest-neighbour tour improved by 2-opt and Or-opt
moves until neither finds a shorter one, so it is never longer than the nearest-first tour the
workshop's bonus asks for.

    >>> tour = plan_tour((0.0, 0.0), [(5.0, 0.0), (1.0, 0.0), (3.0, 0.0)])
    >>> tour.order, tour.length_m, tour.optimal
    ((1, 2, 0), 5.0, True)
    >>> home = [5.0, 1.0, 3.0]  # back to the start from each point: a closed tour
    >>> plan_tour((0.0, 0.0), [(5.0, 0.0), (1.0, 0.0), (3.0, 0.0)], finish=home).length_m
    10.0
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

__all__ = ["EXACT_LIMIT", "Tour", "plan_tour", "tour_length"]

# Held-Karp at 10 points is ~10^5 steps, a few tens of ms in pure Python; at 12 it is ~6x more.
EXACT_LIMIT = 10

# A move must gain more than this to count, so float noise cannot make the search cycle.
_MIN_GAIN_M = 1e-9

# The heuristic runs its local search from this many different first points (the nearest first).
_MAX_STARTS = 10

Point2 = tuple[float, float]


@dataclass(frozen=True)
class Tour:
    """An order to visit the points in: indices into them, the path length (with the finishing
    leg, if any), and whether it is optimal."""

    order: tuple[int, ...]
    length_m: float
    optimal: bool


def plan_tour(
    start: Sequence[float],
    points: Sequence[Sequence[float]],
    *,
    finish: Sequence[float] | None = None,
    exact_limit: int = EXACT_LIMIT,
) -> Tour:
    """The shortest tour from ``start`` over every point (then ``finish[last]`` metres on) that
    we can find.

    Exact (``optimal=True``) for up to ``exact_limit`` points, else 2-opt/Or-opt improved
    nearest-neighbour. Raises ``ValueError`` for a non-finite or malformed coordinate, or a
    ``finish`` that is not one finite, non-negative length per point.
    """
    origin, targets = _validated(start, points)
    ends = _finish(finish, len(targets))
    n = len(targets)
    if n <= 1:
        order: tuple[int, ...] = tuple(range(n))
        return Tour(order, _length(origin, targets, ends, order), True)
    if n <= exact_limit:
        order = _held_karp(origin, targets, ends)
        optimal = True
    else:
        order = _improved(origin, targets, ends)
        optimal = False
    return Tour(order, _length(origin, targets, ends, order), optimal)


def tour_length(
    start: Sequence[float],
    points: Sequence[Sequence[float]],
    order: Sequence[int],
    *,
    finish: Sequence[float] | None = None,
) -> float:
    """Length in metres of the path start -> points[order[0]] -> ... -> points[order[-1]], plus
    ``finish[order[-1]]`` when given.

    ``order`` may visit any subset of the points; an index out of range raises ``ValueError``.
    """
    origin, targets = _validated(start, points)
    ends = _finish(finish, len(targets))
    for index in order:
        if not 0 <= index < len(targets):
            raise ValueError(f"tour index {index} is out of range for {len(targets)} points")
    return _length(origin, targets, ends, order)


# --- validation and distances ---------------------------------------------------------------


def _validated(
    start: Sequence[float], points: Sequence[Sequence[float]]
) -> tuple[Point2, list[Point2]]:
    origin = _point(start, "start")
    return origin, [_point(point, f"point {i}") for i, point in enumerate(points)]


def _point(value: Sequence[float], what: str) -> Point2:
    if len(value) != 2:
        raise ValueError(f"{what} must be (x, y), got {tuple(value)!r}")
    x, y = float(value[0]), float(value[1])
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ValueError(
            f"{what} has a non-finite coordinate ({x}, {y}): positions must be finite numbers"
        )
    return x, y


def _finish(finish: Sequence[float] | None, n: int) -> list[float]:
    if finish is None:
        return [0.0] * n
    if len(finish) != n:
        raise ValueError(f"finish has {len(finish)} lengths for {n} points: one per point")
    lengths = [float(length) for length in finish]
    if not all(math.isfinite(length) and length >= 0.0 for length in lengths):
        raise ValueError(f"finish lengths must be finite and >= 0, got {lengths!r}")
    return lengths


def _length(origin: Point2, targets: Sequence[Point2], ends: Sequence[float], order: Sequence[int]) -> float:
    total = 0.0
    here = origin
    for index in order:
        there = targets[index]
        total += math.dist(here, there)
        here = there
    return total + ends[order[-1]] if order else total


def _distances(origin: Point2, targets: Sequence[Point2]) -> tuple[list[float], list[list[float]]]:
    """Distances from the start to each point, and between every pair of points."""
    from_start = [math.dist(origin, p) for p in targets]
    between = [[math.dist(p, q) for q in targets] for p in targets]
    return from_start, between


# --- exact: Held-Karp -----------------------------------------------------------------------


def _held_karp(origin: Point2, targets: Sequence[Point2], ends: Sequence[float]) -> tuple[int, ...]:
    """The optimal tour: cost[S][j] = shortest path from start over set S ending at j; the tour
    ends at the j that minimises cost[all][j] + ends[j]."""
    n = len(targets)
    from_start, between = _distances(origin, targets)
    full = (1 << n) - 1
    inf = math.inf
    # cost[mask] is a list over the last point j (inf where j is not in mask); parent likewise.
    cost: list[list[float]] = [[inf] * n for _ in range(full + 1)]
    parent: list[list[int]] = [[-1] * n for _ in range(full + 1)]
    for j in range(n):
        cost[1 << j][j] = from_start[j]
    members = [[j for j in range(n) if mask >> j & 1] for mask in range(full + 1)]
    # Pull formulation: to end at j, come from the best k of mask without j. The inner loop is
    # a single pass over a short list of ints, the hot spot of the whole planner.
    for mask in range(3, full + 1):
        inside = members[mask]
        if len(inside) < 2:
            continue
        row = cost[mask]
        back = parent[mask]
        for j in inside:
            prev_mask = mask ^ (1 << j)
            prev = cost[prev_mask]
            to_j = between[j]
            best = inf
            best_k = -1
            for k in members[prev_mask]:
                candidate = prev[k] + to_j[k]
                if candidate < best:
                    best = candidate
                    best_k = k
            row[j] = best
            back[j] = best_k
    last_row = cost[full]
    last = min(range(n), key=lambda j: last_row[j] + ends[j])
    order = []
    mask = full
    while last != -1:
        order.append(last)
        mask, last = mask ^ (1 << last), parent[mask][last]
    order.reverse()
    return tuple(order)


# --- heuristic: nearest neighbour, then 2-opt and Or-opt --------------------------------------
#
# The heuristic works on a path [START, ..., END]: the distance matrix gets the start and an END
# node as its last two rows and columns, dist[j][END] being the finishing leg from j (0 for an
# open tour). Both ends stay in place, so every move has an edge on each side and no move needs
# a special case for the first or the last point.


def _improved(origin: Point2, targets: Sequence[Point2], ends: Sequence[float]) -> tuple[int, ...]:
    """Local search from the nearest-neighbour tour that begins at each of the nearest points.

    One local optimum is often 5-10 % off; a handful of starts usually finds the optimum. The
    first start is at the nearest point, which is the plain nearest-first tour, so the result is
    never longer than that.
    """
    n = len(targets)
    dist = [[math.dist(p, q) for q in targets] + [math.dist(p, origin), ends[j]] for j, p in enumerate(targets)]
    dist.append([math.dist(origin, q) for q in targets] + [0.0, 0.0])  # START = n
    dist.append([*ends, 0.0, 0.0])  # END = n + 1
    firsts = sorted(range(n), key=lambda j: (dist[n][j], j))[:_MAX_STARTS]
    best: list[int] = []
    best_length = math.inf
    for first in firsts:
        path = _nearest_neighbour(dist, first)
        while _two_opt(path, dist) | _or_opt(path, dist):
            pass
        length = sum(dist[a][b] for a, b in itertools.pairwise(path))
        if length < best_length - _MIN_GAIN_M:
            best, best_length = path, length
    return tuple(best[1:-1])


def _nearest_neighbour(dist: list[list[float]], first: int) -> list[int]:
    start, end = len(dist) - 2, len(dist) - 1
    left = set(range(start))
    left.discard(first)
    path = [start, first]
    while left:
        row = dist[path[-1]]
        here = min(left, key=lambda j: (row[j], j))
        path.append(here)
        left.discard(here)
    path.append(end)
    return path


def _two_opt(path: list[int], dist: list[list[float]]) -> bool:
    """Reverse path[i..j] (never an end) while that shortens it; True if anything changed."""
    size = len(path)
    changed = False
    improved = True
    while improved:
        improved = False
        for i in range(1, size - 2):
            for j in range(i + 1, size - 1):
                # Edges (i-1, i) and (j, j+1) become (i-1, j) and (i, j+1).
                a, b, c, d = path[i - 1], path[i], path[j], path[j + 1]
                gain = dist[a][b] + dist[c][d] - dist[a][c] - dist[b][d]
                if gain > _MIN_GAIN_M:
                    path[i : j + 1] = path[j : i - 1 : -1]
                    improved = changed = True
    return changed


def _or_opt(path: list[int], dist: list[list[float]]) -> bool:
    """Move runs of 1-3 points (either way round) elsewhere while that shortens the path."""
    changed = False
    improved = True
    while improved:
        improved = False
        for run in (1, 2, 3):
            i = 1
            while i + run < len(path):
                if _move_run(path, dist, i, run):
                    improved = changed = True
                i += 1
    return changed


def _move_run(path: list[int], dist: list[list[float]], i: int, run: int) -> bool:
    """Move path[i:i+run] to where it shortens the path most, if anywhere; True if moved."""
    size = len(path)
    first, last = path[i], path[i + run - 1]
    prev, end = path[i - 1], i + run
    nxt = path[end]
    gain_out = dist[prev][first] + dist[last][nxt] - dist[prev][nxt]
    row_first, row_last = dist[first], dist[last]
    best_gain = _MIN_GAIN_M
    best: tuple[int, bool] | None = None
    # Insert between path[p] and path[q] for p outside the run, before the END (q is p+1, or the
    # point after the run when p is just before it); the run reversed may also stay where it is.
    for p in range(size - 1):
        if i <= p < end:
            continue
        a = path[p]
        b = path[p + 1 if p + 1 != i else end]
        base = dist[a][b]
        forward = dist[a][first] + row_last[b] - base
        backward = dist[a][last] + row_first[b] - base
        if p != i - 1 and gain_out - forward > best_gain:
            best_gain, best = gain_out - forward, (p, False)
        if gain_out - backward > best_gain:
            best_gain, best = gain_out - backward, (p, True)
    if best is None:
        return False
    p, reverse = best
    segment = path[i:end]
    if reverse:
        segment.reverse()
    del path[i:end]
    after = p if p < i else p - run
    path[after + 1 : after + 1] = segment
    return True
