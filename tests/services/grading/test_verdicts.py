"""A grade in words, JSON and HTML, from a made-up report (no world)."""

from __future__ import annotations

import json
import math
from pathlib import Path

from services.grading.assignment import load_assignment
from services.grading.grade import CriterionResult, GradeReport, SeedFigure, SeedRun
from services.grading.report_html import render_report
from services.grading.run import NodeOutcome, RunResult
from services.grading.verdicts import as_json, format_value, verdict_lines
from tests.services.grading.assignments import shipped
from tests.services.grading.tracks import along, bump, polyline, run


def report(tmp_path: Path, figures: dict[str, list[float]]) -> GradeReport:
    assignment = load_assignment(shipped("wall_follower"))
    tracks = run(along(polyline([(0.0, 0.0), (0.0, 3.5), (-3.0, 3.5)], 0.2), 40.0), bumps=[bump(30.0, -1.0, 3.5)])
    runs = []
    for seed in (1, 2):
        result = RunResult(
            bag=tmp_path / f"seed-{seed}" / "run.mcap", sim_time_s=40.0, wall_time_s=9.5, steps=1200,
            lockstep_lost=0 if seed == 1 else 1, lockstep_reason="" if seed == 1 else "/x: still busy",
            nodes=[NodeOutcome("my.py", True, None if seed == 1 else 1, tmp_path / "node-my.log")],
        )  # fmt: skip
        runs.append(SeedRun(seed, tmp_path / f"seed-{seed}", result, tracks))
    graded = GradeReport(assignment, "ada", ["my.py"], "visible", runs)
    for use in assignment.criteria:
        values = figures[use.name]
        graded.criteria.append(
            CriterionResult(use, [SeedFigure(s, v, f"detail {s}", use.passes(v)) for s, v in zip((1, 2), values, strict=True)])
        )
    return graded


FIGURES = {
    "wall_follower.time_to_wall_s": [17.8, math.inf],
    "wall_follower.band_fraction": [0.93, 0.951],
    "wall_follower.followed_m": [6.2, 4.4],
    "wall_follower.bumps": [0.0, 2.0],
}


def test_format_value() -> None:
    assert [format_value(v) for v in (0.93, 0.8, 3.0, 0.0, math.inf, math.nan, 2.345)] == [
        "0.93", "0.80", "3", "0", "inf", "n/a", "2.35",
    ]  # fmt: skip


def test_a_line_per_criterion_with_the_worst_seed_first(tmp_path: Path) -> None:
    assert verdict_lines(report(tmp_path, FIGURES)) == [
        "FAIL wall_follower.time_to_wall_s inf <= 30  [seed 1: 17.80, seed 2: inf]",
        "PASS wall_follower.band_fraction 0.93 >= 0.80  [seed 1: 0.93, seed 2: 0.95]",
        "PASS wall_follower.followed_m 4.40 >= 4  [seed 1: 6.20, seed 2: 4.40]",
        "FAIL wall_follower.bumps 2 <= 0  [seed 1: 0, seed 2: 2]",
    ]


def test_the_gradebooks_json(tmp_path: Path) -> None:
    record = as_json(report(tmp_path, FIGURES), html="r.html")
    json.dumps(record, allow_nan=False)  # plain JSON: no infinity or NaN anywhere
    assert record["passed"] is False and record["score"] == 0.5
    first = record["criteria"][0]
    assert first["figure"] is None and first["seeds"][1] == {"seed": 2, "figure": None, "passed": False, "detail": "detail 2"}
    assert record["runs"][1]["lockstep"] == {"kept": False, "lost": 1, "reason": "/x: still busy"}
    assert record["runs"][1]["nodes"][0]["exit_code"] == 1


def test_the_page_is_whole_and_says_what_happened(tmp_path: Path) -> None:
    page = render_report(report(tmp_path, FIGURES), tmp_path)
    assert page.startswith("<!doctype html>") and page.endswith("</html>")
    assert "http://" not in page and "https://" not in page and "<script" not in page  # nothing fetched
    assert page.count('<svg class="map"') == 2 and page.count('class="wall"') == 8
    assert page.count('class="trajectory"') == 2 and page.count('class="mark bump"') == 0  # marks come from figures
    assert 'data-name="wall_follower.bumps" data-passed="false"' in page
    assert "not kept in lockstep 1 time(s)" in page
    assert "my.py exited with status 1" in page and "node-my.log" in page
