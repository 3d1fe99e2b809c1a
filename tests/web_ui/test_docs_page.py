"""The core's /docs (Swagger UI) in Chromium: it opens on the world's commands, with the
parameter services and the core's own API after them."""

from __future__ import annotations

import pytest

from tests.web_ui.system import System

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.timeout(60)]


def test_docs_open_on_the_world_s_commands(browser, system: System) -> None:  # type: ignore[no-untyped-def]
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    page = context.new_page()
    try:
        page.goto(system.url + "/docs")
        page.wait_for_selector('h3.opblock-tag[data-tag="node /sim"]', timeout=20_000)
        sections = page.eval_on_selector_all("h3.opblock-tag", "tags => tags.map(tag => tag.dataset.tag)")
        assert sections[:2] == ["node /control", "node /sim"], sections
        assert sections.index("node /control parameters") > sections.index("node /sim")
        assert sections.index("registry") > sections.index("node /sim parameters")
        # the first command on the page is take-off, in view as the page opens
        first = page.locator(".opblock-post").first
        box = first.bounding_box()
        assert "/control/take_off" in first.inner_text() and box is not None and box["y"] + box["height"] < 800, box
    finally:
        context.close()
