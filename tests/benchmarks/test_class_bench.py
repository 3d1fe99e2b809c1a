"""The class rows' measurement (benchmarks/classroom.py) on a small class: its structure and that
every reader was served, never its timings (shared machines: `skydeck bench` reports those)."""

from __future__ import annotations

import pytest

from benchmarks.classroom import measure_class

pytestmark = [pytest.mark.slow, pytest.mark.timeout(240)]


def test_a_small_classs_robots_are_read_at_real_time() -> None:
    reading = measure_class("world", students=3, window_s=1.0)
    assert set(reading["delivery"]) == {"scan", "odom", "bump"}
    assert reading["rtf"] > 0 and reading["rtf_per_cpu"] > 0
    assert all(value > 0 for value in reading["delivery"].values())  # every robot's topics reached the readers


def test_a_small_classs_dashboards_and_class_page_are_served_with_their_tokens() -> None:
    reading = measure_class("dashboards", students=3, window_s=1.0)
    assert reading["closed"] == []  # no dashboard was refused: each read its own robot with its token
    assert all(value > 0 for value in reading["delivery"].values()) and reading["class_view_delivery"] > 0
    assert reading["class_page_p50_ms"] > 0  # GET /api/class answered the instructor
