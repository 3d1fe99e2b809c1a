"""The dashboard with two robots (`skydeck run sim --world robot --robots 2`), driven in Chromium
with the mouse: the map shows both robots, the picker next to the teleop switch chooses which
one's cmd_vel teleop publishes on, and the on-screen pad, held down, drives that robot alone."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

from sim_server.robot.limits import ROBOT_STARTS_M
from tests.sim_server.robot.room import start_room, truth
from tests.web_ui.conftest import Recorder, open_dashboard
from tests.web_ui.system import System

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]

_ROBOTS = "window.skydeck.room.robots"


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "2", "--speed", "1", "--robots", "2")
    yield system
    system.stop()


@pytest.fixture
def dashboard(room: System, browser: object) -> Iterator[tuple[object, Recorder]]:
    ready = f"window.skydeck && {_ROBOTS}.length === 2 && {_ROBOTS}.every((r) => r.pose !== null)"
    with open_dashboard(browser, room.url, ready) as opened:
        yield opened


def _hold(page, key: str) -> None:  # type: ignore[no-untyped-def]
    """Press the pad's ``key`` with the mouse and keep the button down."""
    box = page.locator(f"#teleop-keys kbd[data-key={key}]").bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()


def test_the_pad_drives_the_robot_picked_and_only_that_one(dashboard, room: System) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    assert [r["namespace"] for r in page.evaluate(_ROBOTS)] == ["/robot1", "/robot2"]
    picker = page.locator("#teleop-robot")
    assert picker.is_visible() and picker.input_value() == "/robot1"
    assert page.locator("#teleop-topic").inner_text() == "publishes /robot1/cmd_vel"
    picker.select_option("/robot2")
    assert page.locator("#teleop-topic").inner_text() == "publishes /robot2/cmd_vel"
    # Off, the pad does nothing.
    _hold(page, "up")
    page.mouse.up()
    assert page.evaluate("window.skydeck.teleop")["sent"] == 0
    page.click("#teleop-toggle")
    page.wait_for_function(
        "window.skydeck.sockets().some(s => s.topic === '/robot2/cmd_vel' && s.state === 'open')", timeout=10_000
    )
    # A right click on a key is not a press: nothing held, nothing sent.
    sent = page.evaluate("window.skydeck.teleop")["sent"]
    page.locator("#teleop-keys kbd[data-key=up]").click(button="right")
    assert page.evaluate("window.skydeck.teleop")["held"] == []
    assert page.evaluate("window.skydeck.teleop")["sent"] == sent
    start_x, start_y = ROBOT_STARTS_M[1]
    _hold(page, "up")
    held = page.evaluate("window.skydeck.teleop")
    assert held["held"] == ["up"] and held["twist"]["linear"]["x"] == pytest.approx(0.2)
    page.wait_for_function(f"{_ROBOTS}[1].pose.x > {start_x + 0.3}", timeout=20_000)
    page.mouse.move(5, 5)  # off the pad before letting go: the key it pressed still releases
    page.mouse.up()
    page.wait_for_function("window.skydeck.teleop.held.length === 0", timeout=5_000)
    page.wait_for_function(f"Math.abs({_ROBOTS}[1].odom.v) < 0.01", timeout=10_000)  # released: it stops
    # An arc: forward and left held together (the second with the keyboard's A, the pad's up
    # still pressed), then the pad's stop key ends both.
    _hold(page, "up")
    page.keyboard.down("a")
    page.wait_for_function(f"{_ROBOTS}[1].pose.yaw > 0.4", timeout=20_000)
    page.mouse.up()
    page.keyboard.up("a")
    page.locator("#teleop-keys kbd[data-key=stop]").click()
    page.wait_for_function(f"Math.abs({_ROBOTS}[1].odom.w) < 0.01 && Math.abs({_ROBOTS}[1].odom.v) < 0.01", timeout=10_000)
    x, y, yaw = truth(room, 1)
    assert x > start_x + 0.3 and y > start_y + 0.01 and yaw > 0.4, (x, y, yaw)  # drove, then arced left
    # Robot 1 heard none of it.
    one = truth(room, 0)
    assert math.hypot(one[0] - ROBOT_STARTS_M[0][0], one[1] - ROBOT_STARTS_M[0][1]) < 0.01 and abs(one[2]) < 0.01
    assert recorder.errors == []
