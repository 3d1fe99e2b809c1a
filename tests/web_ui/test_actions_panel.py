"""The dashboard's Actions tab, in Chromium: a goal sent to a course's Fibonacci server (a user
file run by `skydeck run`) shows while it runs, with its ID, status and latest feedback, and its
end shows too."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator

import pytest

from services.launch.background import BackgroundProcess
from tests.ros.conftest import CORPUS, ros_file
from tests.web_ui.conftest import open_dashboard
from tests.web_ui.system import REPO, System

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def system() -> Iterator[System]:
    """A core alone, and the ROS 2 Fibonacci action server (one number every 0.3 s)."""
    from services.runtime.ports import free_port_block

    running = System(free_port_block(1))
    running.start("core", ["core"], running.base_port)
    try:
        with ros_file(running, CORPUS / "ros2" / "fibonacci_action_server.py", "--ros-args", "-p", "step:=0.3", sim_time=False) as server:
            server.wait_for_line("/fibonacci_action_server registered", 30)
            yield running
    finally:
        running.stop()


def test_a_running_goal_shows_with_its_feedback_then_its_end(system: System, browser: object) -> None:
    with open_dashboard(browser, system.url, "window.skydeck && window.skydeck.graph !== null") as (page, recorder):
        page.click("[data-tab=actions]")
        page.wait_for_function("document.querySelector('#action-list tbody').innerText.includes('/fibonacci')", timeout=10_000)
        assert "no goals" in page.inner_text("#action-list")
        sender = BackgroundProcess(
            [sys.executable, "-m", "services.cli", "action", "send_goal", "/fibonacci",
             "example_interfaces/action/Fibonacci", "{order: 8}"],
            name="skydeck action send_goal", cwd=REPO, env={**os.environ, "SKYDECK_CORE_URL": system.url, "PYTHONUNBUFFERED": "1"},
        )  # fmt: skip
        try:
            line = sender.lines[sender.wait_for_line("Goal accepted with ID: ", 30)]
            goal_id = line.split(": ")[1].strip()
            page.wait_for_function(
                f"window.skydeck.actions.some(r => r.goal === '{goal_id}' && r.status === 'EXECUTING' && r.feedback.includes('sequence'))",
                timeout=10_000,
            )
            row = page.locator(f'#action-list tr[data-goal="{goal_id}"]')
            text = row.inner_text()
            assert "/fibonacci" in text and goal_id[:8] in text and "EXECUTING" in text and '"sequence":[0,1,1' in text
            assert row.locator("td").nth(1).get_attribute("title") == goal_id
            assert row.locator("[data-status]").get_attribute("data-status") == "running"
            sender.wait_for_line("Goal finished with status: SUCCEEDED", 30)
            page.wait_for_function(
                f"window.skydeck.actions.some(r => r.goal === '{goal_id}' && r.status === 'SUCCEEDED')", timeout=10_000
            )
            final = next(r for r in page.evaluate("window.skydeck.actions") if r["goal"] == goal_id)
            assert final["feedback"] == '{"sequence":[0,1,1,2,3,5,8,13,21]}'
            assert final["type"] == "example_interfaces/action/Fibonacci"
        finally:
            sender.stop()
        page.click("[data-tab=topics]")  # hidden: the tab reads nothing
        page.wait_for_function(
            "window.skydeck.sockets().every(s => !s.topic.includes('/_action/'))", timeout=10_000
        )
        assert recorder.errors == []
