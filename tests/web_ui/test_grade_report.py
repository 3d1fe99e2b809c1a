"""``skydeck grade``'s HTML report in Chromium: a real grading (a wall follower that drives into
the wall), the page opened from its folder, the trajectory drawn over the room and each
criterion's figure and verdict shown, nothing fetched."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.services.grading.assignments import SOLUTIONS, changed
from tests.web_ui.conftest import Recorder

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.timeout(240)]


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("grade")
    assignment = changed("wall_follower", folder, seeds=[3], duration_s=22)
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "grade", str(assignment), str(SOLUTIONS / "into_the_wall.py"),
         "--student", "grace", "--out", str(folder / "out")],
        capture_output=True, text=True, timeout=200,
    )  # fmt: skip
    assert done.returncode == 1, done.stdout + done.stderr
    return folder / "out" / "report.html"


@pytest.fixture
def page(browser: object, report: Path) -> Iterator[tuple[object, Recorder]]:
    context = browser.new_context(viewport={"width": 1300, "height": 900})  # type: ignore[attr-defined]
    page = context.new_page()
    recorder = Recorder()
    recorder.attach(page)
    page.goto(report.as_uri())
    yield page, recorder
    context.close()


def test_the_report_shows_the_run_over_the_room_and_every_criterion(page: tuple[object, Recorder], report: Path) -> None:
    view, recorder = page
    assert view.title() == "Follow the wall: grace"  # type: ignore[attr-defined]
    assert view.locator("h1 .verdict").inner_text() == "FAIL"  # type: ignore[attr-defined]
    rows = view.locator("tr.criterion")  # type: ignore[attr-defined]
    assert rows.count() == 4
    names = [rows.nth(i).get_attribute("data-name") for i in range(4)]
    assert names == ["wall_follower.time_to_wall_s", "wall_follower.band_fraction", "wall_follower.followed_m", "wall_follower.bumps"]
    bumps = view.locator('tr[data-name="wall_follower.bumps"] td.num').nth(1)  # type: ignore[attr-defined]
    assert bumps.locator(".verdict").inner_text() == "FAIL" and "_front)" in bumps.inner_text()

    svg = view.locator("#seed-3 svg.map")  # type: ignore[attr-defined]
    box = svg.bounding_box()
    assert box is not None and box["width"] > 300 and box["height"] > 300
    assert svg.locator("polygon.wall").count() == 4 and svg.locator("polygon.obstacle").count() >= 1
    points = svg.locator("polyline.trajectory").get_attribute("points").split()
    assert len(points) > 100
    # Drawn where it drove: from the start (the room's middle) towards the +x wall, to the right.
    xs = [float(point.split(",")[0]) for point in points]
    assert xs[-1] - xs[0] > 0.3 * box["width"]  # about half the room (4 m of 8), the map being the room and a margin
    assert svg.locator("polyline.person").count() == 1
    assert svg.locator("g.mark.bump").count() >= 1 and svg.locator("circle.start").count() == 1
    assert "seed-3/run.mcap" in view.locator("#seed-3").inner_text()  # type: ignore[attr-defined]

    assert recorder.errors == []
    assert recorder.urls == [report.as_uri()]  # self-contained: nothing else was fetched
