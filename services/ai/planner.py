"""The AI's tour: visit every box once, starting from the drone, in the shortest order found.

An open tour (the drone does not come back to its start). Up to ``EXACT_LIMIT`` points the
tour is optimal (Held-Karp dynamic programming over subsets, O(n^2 2^n)); beyond that it is a
nearest-neighbour tour improved by 2-opt and Or-opt moves until neither finds a shorter one, so
it is never longer than the nearest-first tour the workshop's bonus asks for.

    >>> tour = plan_tour((0.0, 0.0), [(5.0, 0.0), (1.0, 0.0), (3.0, 0.0)])
    >>> tour.order, tour.length_m, tour.optimal
    ((1, 2, 0), 5.0, True)
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
    """An order to visit the points in: indices into them, the path length, and whether optimal."""

    order: tuple[int, ...]
    length_m: float
    optimal: bool


def plan_tour(
    start: Sequence[float],
    points: Sequence[Sequence[float]],
    *,
    exact_limit: int = EXACT_LIMIT,
) -> Tour:
    """The shortest open tour from ``start`` over every point that we can find.

    Exact (``optimal=True``) for up to ``exact_limit`` points, else 2-opt/Or-opt improved
    nearest-neighbour. Raises ``ValueError`` for a non-finite or malformed coordinate.
    """
    origin, targets = _validated(start, points)
    n = len(targets)
    if n <= 1:
        order: tuple[int, ...] = tuple(range(n))
        return Tour(order, _length(origin, targets, order), True)
    if n <= exact_limit:
        order = _held_karp(origin, targets)
        optimal = True
    else:
        order = _improved(origin, targets)
        optimal = False
    return Tour(order, _length(origin, targets, order), optimal)


def tour_length(start: Sequence[float], points: Sequence[Sequence[float]], order: Sequence[int]) -> float:
    """Length in metres of the open path start -> points[order[0]] -> ... -> points[order[-1]].

    ``order`` may visit any subset of the points; an index out of range raises ``ValueError``.
    """
    origin, targets = _validated(start, points)
    for index in order:
        if not 0 <= index < len(targets):
            raise ValueError(f"tour index {index} is out of range for {len(targets)} points")
    return _length(origin, targets, order)


# --- validation and distances ---------------------------------------------------------------


def _validated(start: Sequence[float], points: Sequence[Sequence[float]]) -> tuple[Point2, list[Point2]]:
    origin = _point(start, "start")
    return origin, [_point(point, f"point {i}") for i, point in enumerate(points)]


def _point(value: Sequence[float], what: str) -> Point2:
    if len(value) != 2:
        raise ValueError(f"{what} must be (x, y), got {tuple(value)!r}")
    x, y = float(value[0]), float(value[1])
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ValueError(f"{what} has a non-finite coordinate ({x}, {y}): positions must be finite numbers")
    return x, y


def _length(origin: Point2, targets: Sequence[Point2], order: Sequence[int]) -> float:
    total = 0.0
    here = origin
    for index in order:
        there = targets[index]
        total += math.dist(here, there)
        here = there
    return total


def _distances(origin: Point2, targets: Sequence[Point2]) -> tuple[list[float], list[list[float]]]:
    """Distances from the start to each point, and between every pair of points."""
    from_start = [math.dist(origin, p) for p in targets]
    between = [[math.dist(p, q) for q in targets] for p in targets]
    return from_start, between


# --- exact: Held-Karp -----------------------------------------------------------------------


def _held_karp(origin: Point2, targets: Sequence[Point2]) -> tuple[int, ...]:
    """The optimal open tour: cost[S][j] = shortest path from start over set S ending at j."""
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
    last = min(range(n), key=last_row.__getitem__)
    order = []
    mask = full
    while last != -1:
        order.append(last)
        mask, last = mask ^ (1 << last), parent[mask][last]
    order.reverse()
    return tuple(order)


# --- heuristic: nearest neighbour, then 2-opt and Or-opt --------------------------------------


def _improved(origin: Point2, targets: Sequence[Point2]) -> tuple[int, ...]:
    """Local search from the nearest-neighbour tour that begins at each point; the best wins.

    One local optimum is often 5-10 % off; a few dozen starts almost always find the optimum's
    neighbourhood. The start at the nearest point is the plain nearest-first tour, so the result
    is never longer than that.
    """
    from_start, between = _distances(origin, targets)
    n = len(targets)
    firsts = sorted(range(n), key=lambda j: (from_start[j], j))[:_MAX_STARTS]
    best: list[int] = []
    best_length = math.inf
    for first in firsts:
        order = _nearest_neighbour(from_start, between, first)
        while _two_opt(order, from_start, between) | _or_opt(order, from_start, between):
            pass
        length = _path_length(order, from_start, between)
        if length < best_length - _MIN_GAIN_M:
            best, best_length = order, length
    return tuple(best)


def _path_length(order: list[int], from_start: list[float], between: list[list[float]]) -> float:
    return from_start[order[0]] + sum(between[a][b] for a, b in itertools.pairwise(order))


def _nearest_neighbour(from_start: list[float], between: list[list[float]], first: int) -> list[int]:
    left = set(range(len(from_start)))
    here = first
    order = [here]
    left.discard(here)
    while left:
        row = between[here]
        here = min(left, key=lambda j: (row[j], j))
        order.append(here)
        left.discard(here)
    return order


def _edge(order: list[int], i: int, j: int, from_start: list[float], between: list[list[float]]) -> float:
    """Length of the edge into position j from position i (i == -1 is the start)."""
    return from_start[order[j]] if i < 0 else between[order[i]][order[j]]


def _two_opt(order: list[int], from_start: list[float], between: list[list[float]]) -> bool:
    """Reverse order[i..j] while that shortens the path; True if anything changed."""
    n = len(order)
    changed = False
    improved = True
    while improved:
        improved = False
        for i in range(n - 1):
            before = _edge(order, i - 1, i, from_start, between)
            for j in range(i + 1, n):
                # Old edges (i-1, i) and (j, j+1) become (i-1, j) and (i, j+1); no j+1 at the end.
                old = before
                new = from_start[order[j]] if i == 0 else between[order[i - 1]][order[j]]
                if j + 1 < n:
                    old += between[order[j]][order[j + 1]]
                    new += between[order[i]][order[j + 1]]
                if new < old - _MIN_GAIN_M:
                    order[i : j + 1] = order[i : j + 1][::-1]
                    before = _edge(order, i - 1, i, from_start, between)
                    improved = changed = True
    return changed


def _or_opt(order: list[int], from_start: list[float], between: list[list[float]]) -> bool:
    """Move runs of 1-3 points (either way round) elsewhere while that shortens the path."""
    changed = False
    improved = True
    while improved:
        improved = False
        n = len(order)
        for size in (1, 2, 3):
            for i in range(n - size + 1):
                gain, move = _best_move(order, i, size, from_start, between)
                if gain > _MIN_GAIN_M and move is not None:
                    _apply_move(order, i, size, *move)
                    improved = changed = True
                    break
            if improved:
                break
    return changed


def _cost(a: int, b: int, from_start: list[float], between: list[list[float]]) -> float:
    """Distance from node a (-1: the start) to point b."""
    return from_start[b] if a < 0 else between[a][b]


def _best_move(
    order: list[int], i: int, size: int, from_start: list[float], between: list[list[float]]
) -> tuple[float, tuple[int, bool] | None]:
    """The best place to reinsert order[i:i+size]: (gain, (insert after position, reversed))."""
    n = len(order)
    first, last = order[i], order[i + size - 1]
    prev = order[i - 1] if i > 0 else -1
    nxt = order[i + size] if i + size < n else None
    removed = _cost(prev, first, from_start, between)
    if nxt is not None:
        removed += between[last][nxt] - _cost(prev, nxt, from_start, between)
    rest = order[:i] + order[i + size :]
    best_gain, best_move = 0.0, None
    # Insert between rest[p-1] and rest[p] (p == 0: right after the start; p == len: at the end).
    for p in range(len(rest) + 1):
        a = rest[p - 1] if p > 0 else -1
        b = rest[p] if p < len(rest) else None
        for reverse in (False, True):
            if p == i and not reverse:
                continue  # the segment where it already is
            head, tail = (last, first) if reverse else (first, last)
            added = _cost(a, head, from_start, between)
            if b is not None:
                added += between[tail][b] - _cost(a, b, from_start, between)
            gain = removed - added
            if gain > best_gain:
                best_gain, best_move = gain, (p, reverse)
    return best_gain, best_move


def _apply_move(order: list[int], i: int, size: int, p: int, reverse: bool) -> None:
    segment = order[i : i + size]
    if reverse:
        segment.reverse()
    del order[i : i + size]
    order[p:p] = segment
