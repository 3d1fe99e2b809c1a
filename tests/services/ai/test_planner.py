"""The tour planner: exact against brute force, the heuristic against exact and nearest-first."""

from __future__ import annotations

import itertools
import math
import random

import pytest

from services.ai.planner import EXACT_LIMIT, Tour, plan_tour, tour_length


def _random_instance(
    rng: random.Random, n: int
) -> tuple[tuple[float, float], list[tuple[float, float]]]:
    start = (rng.uniform(-15, 15), rng.uniform(-15, 15))
    return start, [(rng.uniform(-15, 15), rng.uniform(-15, 15)) for _ in range(n)]


def _brute_force(start, points) -> float:
    if not points:
        return 0.0
    return min(
        tour_length(start, points, order) for order in itertools.permutations(range(len(points)))
    )


def _nearest_first(start, points) -> float:
    """The seed's bonus: always fly to the closest box not yet visited."""
    left = list(range(len(points)))
    here, total = start, 0.0
    while left:
        nearest = min(left, key=lambda i: math.dist(here, points[i]))
        total += math.dist(here, points[nearest])
        here = points[nearest]
        left.remove(nearest)
    return total


def _is_permutation(order: tuple[int, ...], n: int) -> bool:
    return sorted(order) == list(range(n))


# --- exact ----------------------------------------------------------------------------------


@pytest.mark.parametrize("n", range(0, 9))
def test_exact_matches_brute_force(n: int) -> None:
    rng = random.Random(1000 + n)
    for _ in range(25 if n <= 6 else 6):
        start, points = _random_instance(rng, n)
        tour = plan_tour(start, points)
        assert tour.optimal
        assert _is_permutation(tour.order, n)
        assert tour.length_m == pytest.approx(_brute_force(start, points), abs=1e-9)
        assert tour.length_m == pytest.approx(tour_length(start, points, tour.order), abs=1e-12)


def test_exact_on_a_line_goes_out_in_order() -> None:
    tour = plan_tour((0.0, 0.0), [(5.0, 0.0), (1.0, 0.0), (3.0, 0.0)])
    assert tour == Tour(order=(1, 2, 0), length_m=5.0, optimal=True)


def test_open_tour_does_not_return_to_start() -> None:
    # A closed tour would not care which end it starts from; the open one starts near the drone.
    tour = plan_tour((0.0, 0.0), [(10.0, 0.0), (1.0, 0.0)])
    assert tour.order == (1, 0)
    assert tour.length_m == pytest.approx(10.0)


def test_exact_beats_nearest_first_where_greed_fails() -> None:
    # Nearest-first goes right to 1, back to -2, then all the way to 10: 1 + 3 + 12 = 16.
    # Going left first: 2 + 3 + 9 = 14.
    start = (0.0, 0.0)
    points = [(1.0, 0.0), (-2.0, 0.0), (10.0, 0.0)]
    tour = plan_tour(start, points)
    assert tour.order == (1, 0, 2)
    assert tour.length_m == pytest.approx(14.0)
    assert _nearest_first(start, points) == pytest.approx(16.0)


# --- edge cases -----------------------------------------------------------------------------


def test_no_points() -> None:
    assert plan_tour((1.0, 2.0), []) == Tour(order=(), length_m=0.0, optimal=True)
    assert tour_length((1.0, 2.0), [], ()) == 0.0


def test_one_point() -> None:
    assert plan_tour((0.0, 0.0), [(3.0, 4.0)]) == Tour(order=(0,), length_m=5.0, optimal=True)


def test_duplicate_points_are_each_visited() -> None:
    points = [(3.0, 4.0), (3.0, 4.0), (0.0, 1.0), (3.0, 4.0)]
    tour = plan_tour((0.0, 0.0), points)
    assert _is_permutation(tour.order, 4)
    assert tour.length_m == pytest.approx(1.0 + math.dist((0.0, 1.0), (3.0, 4.0)))


def test_duplicates_in_the_heuristic() -> None:
    points = [(float(i % 5), 0.0) for i in range(25)]
    tour = plan_tour((0.0, 0.0), points)
    assert not tour.optimal
    assert _is_permutation(tour.order, 25)
    assert tour.length_m == pytest.approx(4.0)


def test_all_points_at_the_start() -> None:
    tour = plan_tour((2.0, 2.0), [(2.0, 2.0)] * 3)
    assert _is_permutation(tour.order, 3)
    assert tour.length_m == 0.0


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_point_is_refused(bad: float) -> None:
    with pytest.raises(ValueError, match=r"point 1 has a non-finite coordinate"):
        plan_tour((0.0, 0.0), [(1.0, 1.0), (bad, 0.0)])
    with pytest.raises(ValueError, match=r"point 0 has a non-finite coordinate"):
        tour_length((0.0, 0.0), [(0.0, bad)], (0,))


def test_non_finite_start_is_refused() -> None:
    with pytest.raises(ValueError, match=r"start has a non-finite coordinate"):
        plan_tour((math.nan, 0.0), [(1.0, 1.0)])


def test_malformed_point_is_refused() -> None:
    with pytest.raises(ValueError, match=r"point 0 must be \(x, y\)"):
        plan_tour((0.0, 0.0), [(1.0, 2.0, 3.0)])  # type: ignore[list-item]


def test_tour_length_rejects_an_index_out_of_range() -> None:
    with pytest.raises(ValueError, match="out of range"):
        tour_length((0.0, 0.0), [(1.0, 1.0)], (1,))


def test_tour_length_of_a_partial_order() -> None:
    assert tour_length((0.0, 0.0), [(3.0, 4.0), (6.0, 8.0)], (1,)) == pytest.approx(10.0)


# --- heuristic ------------------------------------------------------------------------------


@pytest.mark.parametrize("n", [9, 10])
def test_heuristic_is_close_to_optimal_and_never_worse_than_nearest_first(n: int) -> None:
    rng = random.Random(2000 + n)
    ratios = []
    for _ in range(20):
        start, points = _random_instance(rng, n)
        exact = plan_tour(start, points)
        heuristic = plan_tour(start, points, exact_limit=0)
        assert exact.optimal and not heuristic.optimal
        assert _is_permutation(heuristic.order, n)
        assert heuristic.length_m >= exact.length_m - 1e-9
        assert heuristic.length_m <= _nearest_first(start, points) + 1e-9
        ratios.append(heuristic.length_m / exact.length_m)
    assert max(ratios) < 1.05, f"worst heuristic/optimal ratio {max(ratios):.3f}"
    assert sum(ratios) / len(ratios) < 1.01


def test_above_the_exact_limit_the_heuristic_is_used() -> None:
    start, points = _random_instance(random.Random(7), EXACT_LIMIT + 1)
    tour = plan_tour(start, points)
    assert not tour.optimal
    assert _is_permutation(tour.order, EXACT_LIMIT + 1)


def test_thirty_points_complete_as_a_permutation() -> None:
    rng = random.Random(30)
    for _ in range(5):
        start, points = _random_instance(rng, 30)
        tour = plan_tour(start, points)
        assert _is_permutation(tour.order, 30)
        assert tour.length_m == pytest.approx(tour_length(start, points, tour.order))
        assert tour.length_m <= _nearest_first(start, points) + 1e-9


def test_the_tour_is_frozen() -> None:
    tour = plan_tour((0.0, 0.0), [(1.0, 0.0)])
    with pytest.raises(AttributeError):
        tour.length_m = 0.0  # type: ignore[misc]


def test_heuristic_finds_the_straight_line_through_shuffled_points() -> None:
    points = [(float(x), 0.0) for x in range(1, 41)]
    random.Random(3).shuffle(points)
    tour = plan_tour((0.0, 0.0), points)
    assert not tour.optimal
    assert tour.length_m == pytest.approx(40.0)
    assert [points[i][0] for i in tour.order] == [float(x) for x in range(1, 41)]


# --- finishing legs (landing beside the last box, or a closed tour home) ---------------------


def _brute_force_with_finish(start, points, finish) -> float:
    return min(
        tour_length(start, points, order, finish=finish)
        for order in itertools.permutations(range(len(points)))
    )


@pytest.mark.parametrize("n", range(1, 8))
def test_exact_with_finishing_legs_matches_brute_force(n: int) -> None:
    rng = random.Random(3000 + n)
    for _ in range(10):
        start, points = _random_instance(rng, n)
        finish = [rng.uniform(0, 10) for _ in range(n)]
        tour = plan_tour(start, points, finish=finish)
        assert tour.optimal and _is_permutation(tour.order, n)
        assert tour.length_m == pytest.approx(_brute_force_with_finish(start, points, finish), abs=1e-9)


def test_a_closed_tour_is_shorter_than_the_open_one_plus_the_way_back() -> None:
    """Flying the best open tour and then home (what the AI did) is often longer than the best
    closed tour; planning with the finishing legs finds the latter."""
    rng = random.Random(77)
    gains = []
    for _ in range(30):
        start, points = _random_instance(rng, 6)
        home = [math.dist(p, start) for p in points]
        open_tour = plan_tour(start, points)
        open_then_home = open_tour.length_m + home[open_tour.order[-1]]
        closed = plan_tour(start, points, finish=home)
        assert closed.length_m == pytest.approx(tour_length(start, points, closed.order, finish=home))
        assert closed.length_m <= open_then_home + 1e-9
        gains.append(open_then_home - closed.length_m)
    assert sum(gain > 0.5 for gain in gains) >= 5


@pytest.mark.parametrize("n", [9, 12])
def test_heuristic_with_finishing_legs_is_close_to_optimal(n: int) -> None:
    rng = random.Random(4000 + n)
    ratios = []
    for _ in range(10):
        start, points = _random_instance(rng, n)
        finish = [math.dist(p, start) for p in points]
        heuristic = plan_tour(start, points, finish=finish, exact_limit=0)
        exact = plan_tour(start, points, finish=finish, exact_limit=12)
        assert _is_permutation(heuristic.order, n)
        assert heuristic.length_m == pytest.approx(tour_length(start, points, heuristic.order, finish=finish))
        assert heuristic.length_m >= exact.length_m - 1e-9
        ratios.append(heuristic.length_m / exact.length_m)
    assert max(ratios) < 1.05, f"worst heuristic/optimal ratio {max(ratios):.3f}"


def test_bad_finishing_legs_are_refused() -> None:
    with pytest.raises(ValueError, match="one per point"):
        plan_tour((0.0, 0.0), [(1.0, 1.0)], finish=[1.0, 2.0])
    with pytest.raises(ValueError, match="finite and >= 0"):
        plan_tour((0.0, 0.0), [(1.0, 1.0)], finish=[math.nan])
