"""The dashboard in the robot world (core + `skydeck run sim --world robot`), driven in Chromium:
the map shows the room, the robot, the person and the scan; teleop drives /cmd_vel; the commands
panel shows the robot world's services. Waits are on `window.skydeck`, never fixed sleeps."""

from __future__ import annotations

from collections.abc import Iterator
from urllib.parse import urlsplit

import pytest

from tests.sim_server.robot.room import call, latest, start_room, truth
from tests.web_ui.conftest import Recorder, open_dashboard
from tests.web_ui.system import System
from tests.web_ui.view3d_page import open_3d, wait_view
from tests.web_ui.world_names import read_topics, untyped_topics, world_topics

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "1", "--speed", "1")
    yield system
    system.stop()


@pytest.fixture
def dashboard(room: System, browser: object) -> Iterator[tuple[object, Recorder]]:
    """A fresh page on the dashboard, once it shows the robot."""
    ready = (
        "window.skydeck && window.skydeck.world.kind === 'robot' && window.skydeck.room.robots.length === 1"
        " && window.skydeck.room.robots[0].pose !== null"
    )
    with open_dashboard(browser, room.url, ready) as opened:
        yield opened


def test_the_map_shows_the_room_the_robot_the_person_and_the_scan(dashboard, room: System) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    page.wait_for_function(
        "(() => { const r = window.skydeck.room;"
        " return r.robots[0].scanPoints > 100 && r.robots[0].odom && r.people.length === 1 && r.obstacles.length > 0; })()",
        timeout=15_000,
    )
    shown = page.evaluate("window.skydeck.room")
    assert len(shown["obstacles"]) == latest(room, "/simulator/world")["boxes"]
    assert shown["robots"][0]["namespace"] == "/"
    page.wait_for_function("window.skydeck.mapFrames > 10 && window.skydeck.coreReachable", timeout=10_000)
    page.wait_for_function("document.querySelector('#status-banner').dataset.state === 'ok'", timeout=10_000)
    # The commands panel: the robot world's services only.
    assert page.locator("#reset").is_visible()
    for drone_only in ("#takeoff", "#land", "#mission-start", "#mission-stop", "#mission-status"):
        assert page.locator(drone_only).is_hidden(), drone_only
    page.wait_for_function("document.querySelector('#drone-summary').textContent.includes('robot: x')", timeout=10_000)
    assert recorder.errors == []
    core = urlsplit(room.url).netloc
    assert [u for u in recorder.urls if not u.startswith("data:") and urlsplit(u).netloc != core] == []
    assert any(u.startswith(f"ws://{core}/scan") for u in recorder.urls)


def test_teleop_keys_drive_the_robot_on_cmd_vel(dashboard, room: System) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    call(room, "/simulator/reset")
    page.wait_for_function("Math.abs(window.skydeck.room.robots[0].pose.x) < 0.01", timeout=10_000)
    assert page.locator("#teleop-topic").inner_text() == "publishes /cmd_vel"
    page.click("#teleop-toggle")
    page.wait_for_function("window.skydeck.sockets().some(s => s.topic === '/cmd_vel' && s.state === 'open')", timeout=10_000)
    page.locator("#map").hover()
    page.evaluate("document.activeElement.blur()")
    page.keyboard.down("w")
    page.wait_for_function("window.skydeck.room.robots[0].pose.x > 0.3", timeout=20_000)
    twist = page.evaluate("window.skydeck.teleop.twist")
    assert twist["linear"]["x"] == pytest.approx(0.2) and twist["angular"]["z"] == 0  # body frame, forward
    page.keyboard.up("w")
    page.keyboard.down("a")  # turn left on the spot
    page.wait_for_function("window.skydeck.room.robots[0].pose.yaw > 0.5", timeout=20_000)
    page.keyboard.up("a")
    x, y, yaw = truth(room)
    assert x > 0.3 and abs(y) < 0.05 and yaw > 0.5
    # Released: the robot stops (one zero Twist, and the watchdog besides).
    page.wait_for_function("Math.abs(window.skydeck.room.robots[0].odom.w) < 0.01", timeout=10_000)
    assert page.evaluate("window.skydeck.room.robots[0].trail") > 5  # the odometry trail is drawn


def test_the_reset_button_brings_the_robot_back(dashboard, room: System) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    page.click("#reset")
    page.wait_for_function("document.querySelector('#command-result').dataset.kind === 'success'", timeout=10_000)
    assert "robots at their starts" in page.locator("#command-result").inner_text()
    page.wait_for_function("Math.hypot(window.skydeck.room.robots[0].pose.x, window.skydeck.room.robots[0].pose.y) < 0.01", timeout=10_000)


def test_the_page_reads_only_the_robot_worlds_names_and_makes_no_ghost_topic(dashboard, room: System) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    page.check("#camera-toggle")
    page.wait_for_function("window.skydeck.sockets().some(s => s.topic.startsWith('/simulator/camera') && s.state === 'open')", timeout=10_000)
    open_3d(page)  # the 3D view's world and TF too
    wait_view(page, "v.world.robot.robots.length === 1")
    read = read_topics(recorder.urls, room.url)
    assert {"/scan", "/odom", "/simulator/world", "/simulator/obstacles", "/tf"} <= read, read
    assert read & world_topics(room.url, "drone") == set(), "the drone world's names, read in the robot world"
    assert untyped_topics(room.url) == []
