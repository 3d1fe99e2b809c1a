"""The ball tracker of examples/robot (written as the course's computer-vision day writes one:
rclpy, cv_bridge, an HSV threshold tuned with trackbars, imshow of the image and the mask,
cmd_vel) run by ``skydeck run`` in the soccer room: it finds the ball in the robot's camera and
drives into it, pushing it along with the robot's motors; meanwhile its OpenCV windows are live
panels in the dashboard's Windows tab, in Chromium."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

pytest.importorskip("cv2", reason="the vision extra is not installed: make install-vision")

from sim_server.soccer.limits import BALL_START_M  # noqa: E402
from tests.ros.conftest import no_skydeck_frames, ros_file  # noqa: E402
from tests.sim_server.robot.room import latest, wait_for  # noqa: E402
from tests.web_ui.conftest import open_dashboard  # noqa: E402
from tests.web_ui.system import REPO, System, started  # noqa: E402

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(180)]

TRACKER = REPO / "examples" / "robot" / "ball_tracker.py"


@pytest.fixture(scope="module")
def soccer() -> Iterator[System]:
    with started(("sim", ["run", "sim", "--world", "soccer", "--seed", "1", "--camera-rate", "10"])) as system:
        wait_for(system, "/simulator/balls", lambda m: True)
        yield system


def _ball(system: System) -> tuple[float, float]:
    position = latest(system, "/simulator/balls")["poses"][0]["position"]  # type: ignore[index]
    return position["x"], position["y"]


def _robot(system: System) -> tuple[float, float]:
    position = latest(system, "/simulator/robots")["poses"][0]["position"]  # type: ignore[index]
    return position["x"], position["y"]


def test_the_ball_tracker_pushes_the_ball_and_its_windows_are_in_the_dashboard(soccer: System, browser: object) -> None:
    assert _ball(soccer) == pytest.approx(BALL_START_M, abs=1e-3)
    start_gap = math.dist(_robot(soccer), BALL_START_M)
    with (
        ros_file(soccer, TRACKER, sim_time=False) as tracker,
        open_dashboard(browser, soccer.url, "window.skydeck && window.skydeck.coreReachable") as (page, recorder),
    ):
        # The soccer room extends the robot world: the dashboard shows it as that world.
        page.wait_for_function("window.skydeck.world.kind === 'robot' && window.skydeck.room.robots.length === 1", timeout=20_000)  # type: ignore[attr-defined]
        page.click("button[data-tab='windows']")  # type: ignore[attr-defined]
        page.wait_for_function(  # type: ignore[attr-defined]
            "['video_window', 'binary_window'].every(n => window.skydeck.windows.some(w => w.name === n && w.frames > 2))",
            timeout=60_000,
        )
        windows = {w["name"]: w for w in page.evaluate("window.skydeck.windows")}  # type: ignore[attr-defined]
        assert set(windows) == {"video_window", "binary_window", "image_info"}
        assert {w["node"] for w in windows.values()} == {"/ball_tracker"}
        assert (windows["video_window"]["width"], windows["video_window"]["height"]) == (320, 240)
        assert windows["video_window"]["mouse"] is True
        sliders = {t["name"]: (t["value"], t["maximum"], t["slider"]) for t in windows["binary_window"]["trackbars"]}
        assert sliders == {
            "hue lower": (0, 179, 0), "hue upper": (12, 179, 12),
            "saturation lower": (150, 255, 150), "saturation upper": (255, 255, 255),
            "value lower": (80, 255, 80), "value upper": (255, 255, 255),
        }  # fmt: skip

        # The robot drives into the ball and pushes it, by contact alone.
        ball = wait_for(
            soccer, "/simulator/balls",
            lambda m: math.dist((m["poses"][0]["position"]["x"], m["poses"][0]["position"]["y"]), BALL_START_M) > 0.5,
            timeout_s=90,
        )["poses"][0]["position"]  # fmt: skip
        assert ball["x"] > BALL_START_M[0] + 0.4  # along +x, ahead of where the robot started
        assert math.dist(_robot(soccer), _ball(soccer)) < start_gap

        # Tuned from the dashboard: with no hue allowed, the mask is black and the tracker turns
        # on the spot looking for the ball (its trackbar callback ran, its loop acted on it).
        page.locator(".cv-window[data-window='binary_window'] input[data-trackbar='hue upper']").fill("0")  # type: ignore[attr-defined]
        wait_for(soccer, "/cmd_vel", lambda m: m["linear"]["x"] == 0.0 and m["angular"]["z"] == pytest.approx(0.35), timeout_s=30)
        assert recorder.errors == []
    assert no_skydeck_frames(tracker.lines) and not any("Traceback" in line for line in tracker.lines), tracker.tail()
