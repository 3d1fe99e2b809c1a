"""The access token: asked for once in a dialog, kept for the tab, sent on fetch and sockets.

A system of its own (core and control, both with ``SKYDECK_TOKEN``): reading stays open,
service calls and publishing need the token.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.conftest import free_port_block
from tests.web_ui.system import System, answered

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]

TOKEN = "workshop-secret"


@pytest.fixture(scope="module")
def token_system(tmp_path_factory: pytest.TempPathFactory) -> Iterator[System]:
    base = free_port_block(5)
    running = System(base)
    try:
        running.start("core", ["core"], base, env={"SKYDECK_TOKEN": TOKEN})
        running.start("control", ["run", "control"], base + 3, env={"SKYDECK_TOKEN": TOKEN})
        yield running
    finally:
        running.stop()


def test_token_is_asked_once_and_then_sent(token_system: System, browser) -> None:  # type: ignore[no-untyped-def]
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    try:
        page = context.new_page()
        page.goto(token_system.url + "/")
        page.locator('#service-list tr[data-service="/control/take_off"]').wait_for(timeout=10_000)

        # Without a token the call is refused with 401: the dialog asks; cancelling shows the error.
        page.click("#takeoff")
        page.locator("#token-dialog[open]").wait_for(timeout=10_000)
        assert "token" in page.inner_text("#token-reason")
        page.click("#token-dialog button[value=cancel]")
        page.wait_for_function(answered("/control/take_off"), timeout=10_000)
        assert page.get_attribute("#command-result", "data-kind") == "error"
        assert "401" in page.inner_text("#command-result")

        # With the token the call goes through (control answers: success or a refusal, no error).
        page.click("#takeoff")
        page.locator("#token-dialog[open]").wait_for(timeout=10_000)
        page.fill("#token-input", TOKEN)
        page.click("#token-save")
        page.wait_for_function(answered("/control/take_off"), timeout=10_000)
        assert page.get_attribute("#command-result", "data-kind") in ("success", "refused")
        assert page.evaluate("sessionStorage.getItem('skydeck.token')") == TOKEN

        # Kept for the tab: after a reload no dialog, and sockets carry ?token=.
        page.reload()
        page.wait_for_function("window.skydeck && window.skydeck.coreReachable", timeout=10_000)
        urls: list[str] = []
        page.on("websocket", lambda websocket: urls.append(websocket.url))
        page.click("#land")
        page.wait_for_function(answered("/control/land"), timeout=10_000)
        assert page.locator("#token-dialog[open]").count() == 0
        assert page.get_attribute("#command-result", "data-kind") in ("success", "refused")
        page.click("#teleop-toggle")
        page.wait_for_function(
            "window.skydeck.sockets().some(s => s.topic === '/drone/cmd_vel' && s.state === 'open')", timeout=10_000
        )
        assert any("/drone/cmd_vel" in url and f"token={TOKEN}" in url for url in urls)
    finally:
        context.close()
