"""The soak's rows from RSS samples (the run itself: test_bench_smoke's short soak)."""

from __future__ import annotations

import pytest

from benchmarks.soak import _one_name_per_process, _summarise


def _line(start_mib: float, mib_per_min: float) -> list[tuple[float, float]]:
    """A sample every 5 s for 10 minutes, on a straight line."""
    return [(t, start_mib + mib_per_min * t / 60) for t in range(0, 601, 5)]


def test_the_slope_row_is_the_process_that_grows_most_for_its_size() -> None:
    # The core gains more MiB a minute, but the small node grows by a larger share of itself.
    rows = {r.name: r for r in _summarise({"/skydeck_core": _line(500, 2.0), "/ai": _line(20, 0.5)}, 600, {})}
    slope = rows["soak_rss_slope"]
    assert (slope.value, slope.unit, slope.reference_value) == (pytest.approx(0.5), "MiB/min", pytest.approx(21))
    assert slope.detail["process"] == "/ai" and slope.detail["fitted_growth"] == pytest.approx(4 / 21)
    assert slope.met is False  # 4 MiB over the 8 measured minutes: 19% of the 21 MiB after warm-up
    assert rows["soak_rss_ai"].met is False and rows["soak_rss_skydeck_core"].met is True


def test_a_flat_run_passes_and_warm_up_growth_does_not_count() -> None:
    warming = [(t, 100.0 if t >= 120 else 50 + t / 3) for t in range(0, 601, 5)]  # grows, then flat
    rows = {r.name: r for r in _summarise({"/sim": warming, "/control": _line(40, 0.0)}, 600, {"frames": 7})}
    assert rows["soak_rss_slope"].met is True and rows["soak_rss_slope"].value == pytest.approx(0.0)
    assert rows["soak_rss_sim"].met is True and rows["soak_rss_sim"].detail["frames"] == 7


def test_each_process_is_measured_once_and_the_core_by_its_own_name() -> None:
    # /rosapi is served by the core's process: one row for that process, named /skydeck_core.
    nodes = [
        {"name": "/rosapi", "pid": 10},
        {"name": "/skydeck_core", "pid": 10},
        {"name": "/sim", "pid": 11},
        {"name": "/ai", "pid": 12},
        {"name": "/ai_helper", "pid": 12},
    ]
    assert _one_name_per_process(nodes) == {"/skydeck_core": 10, "/sim": 11, "/ai": 12}
