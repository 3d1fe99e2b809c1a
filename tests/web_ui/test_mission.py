"""The whole workshop system (sim, perception, control, AI) seen on the dashboard: the planned
tour, boxes turning visited, mission stop and start from the buttons. Also takes the docs'
screenshot, since this is the view a student keeps open.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from tests.conftest import free_port_block
from tests.web_ui.system import REPO, System, answered

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(180)]

# The README's screenshot is refreshed only on request, so a test run never edits tracked files.
DOCS_SCREENSHOT = REPO / "docs" / "img" / "dashboard.png"


@pytest.fixture(scope="module")
def system(tmp_path_factory: pytest.TempPathFactory) -> Iterator[System]:
    """Overrides the conftest's: every node of the workshop, the AI's progress in a fresh folder."""
    base = free_port_block(5)
    running = System(base)
    state = {"SKYDECK_STATE_DIR": str(tmp_path_factory.mktemp("ai_state"))}
    try:
        running.start("core", ["core"], base)
        running.start("sim", ["run", "sim", "--speed", "1", "--seed", "1"], base + 1)
        running.start("perception", ["run", "perception"], base + 2)
        running.start("control", ["run", "control"], base + 3)
        running.start("ai", ["run", "ai", "--start-mission"], base + 4, env=state)
        yield running
    finally:
        running.stop()


def test_mission_progress_is_drawn(dashboard, my_point, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    page.wait_for_function("window.skydeck.boxes.perception.length === 8", timeout=20_000)
    page.wait_for_function(
        "() => { const s = window.skydeck.aiStatus; return s && s.state === 'flying' && s.tour.length > 0; }",
        timeout=60_000,
    )
    status = page.evaluate("window.skydeck.aiStatus")
    assert set(status["tour"]) <= set(range(8))
    page.wait_for_function("window.skydeck.aiStatus.visited.length >= 2", timeout=90_000)
    text = page.inner_text("#mission-status")
    assert "flying" in text and "boxes visited" in text
    assert page.get_attribute("#mission-status", "data-state") == "flying"

    # The docs' picture: the mission under way, the seed's point as a layer, the camera on.
    page.click("[data-tab=layers]")
    page.wait_for_function(
        "document.querySelector('#add-topic-select option[value=\"/my_point\"]') !== null", timeout=10_000
    )
    page.select_option("#add-topic-select", "/my_point")
    page.click("#add-topic")
    page.wait_for_function("window.skydeck.layers().some(l => l.topic === '/my_point' && l.count === 1)", timeout=10_000)
    page.check("#camera-toggle")
    page.wait_for_function("window.skydeck.camera.frames > 2", timeout=20_000)
    page.click("[data-tab=topics]")
    page.wait_for_function("window.skydeck.aiStatus.visited.length >= 3", timeout=60_000)
    screenshot = DOCS_SCREENSHOT if os.environ.get("SKYDECK_UPDATE_SCREENSHOTS") == "1" else tmp_path / "dashboard.png"
    screenshot.parent.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(screenshot))
    assert screenshot.stat().st_size > 10_000
    assert recorder.errors == []


def test_mission_stop_and_start_buttons(dashboard) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    page.wait_for_function("window.skydeck.aiStatus !== null", timeout=20_000)
    page.click("#mission-stop")
    page.wait_for_function(answered("/ai/stop"), timeout=10_000)
    assert page.get_attribute("#command-result", "data-kind") == "success"
    page.wait_for_function("window.skydeck.aiStatus.state === 'idle'", timeout=10_000)
    page.click("#mission-start")
    page.wait_for_function(answered("/ai/start"), timeout=10_000)
    assert page.get_attribute("#command-result", "data-kind") == "success"
    page.wait_for_function("['taking_off', 'flying', 'done'].includes(window.skydeck.aiStatus.state)", timeout=30_000)


def test_the_reset_button_starts_a_new_tour_over_the_new_boxes(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    """The dashboard's reset builds a new world: the AI flies a new tour by itself (issue 21)."""
    page, _ = dashboard
    page.wait_for_function("window.skydeck.aiStatus && window.skydeck.aiStatus.visited.length >= 1", timeout=90_000)
    before = httpx.get(system.url + "/simulator/world", timeout=5).json()["id"]
    page.click("#reset")
    page.wait_for_function(answered("/simulator/reset"), timeout=10_000)
    assert page.get_attribute("#command-result", "data-kind") == "success"
    after = httpx.get(system.url + "/simulator/world", timeout=5).json()["id"]
    assert after != before and after in page.inner_text("#command-result")
    # No /ai/start: the new world's tour begins from no box visited, and visits the new boxes.
    page.wait_for_function(
        "() => { const s = window.skydeck.aiStatus; return s.state === 'flying' && s.visited.length === 0; }",
        timeout=30_000,
    )
    page.wait_for_function("window.skydeck.aiStatus.visited.length >= 1", timeout=60_000)
