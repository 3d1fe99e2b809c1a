"""The dashboard with recordings: its views follow a recording being played, and its recorder
panel records, lists and serves a file. Real core, real `skydeck bag play`, real Chromium."""

from __future__ import annotations

import math
import os
import signal
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from services.bag import BagReader, BagWriter
from services.launch.background import BackgroundProcess
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, Pose, PoseStamped
from shared_models.std_msgs import Header
from tests.conftest import free_port_block
from tests.web_ui.conftest import Recorder, open_dashboard
from tests.web_ui.system import REPO, System

pytestmark = [pytest.mark.browser, pytest.mark.timeout(120)]

MAGIC = b"\x89MCAP0\r\n"


def circle_bag(path: Path) -> Path:
    """Three seconds of a drone flying a circle 3 m up: /drone/pose at 30 Hz."""
    writer = BagWriter.create(path, metadata={})
    pose = writer.add_topic("/drone/pose", "geometry_msgs/msg/PoseStamped")
    start_ns = time.time_ns()
    for i in range(90):
        angle = i / 90 * 2 * math.pi
        message = PoseStamped(
            header=Header(seq=i + 1, stamp=Time.from_sec(i / 30), frame_id="map"),
            pose=Pose(position=Point(x=5 * math.cos(angle), y=5 * math.sin(angle), z=3.0)),
        )
        writer.write(pose, message.model_dump_json(), start_ns + i * 33_333_333)
    writer.close()
    return path


@pytest.fixture(scope="module")
def recordings(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[System, Path, BackgroundProcess]]:
    """A core (recordings in a temporary folder) and `skydeck bag play --loop` of a circle."""
    folder = tmp_path_factory.mktemp("recordings")
    bag = circle_bag(tmp_path_factory.mktemp("bags") / "circle.mcap")
    running = System(free_port_block(1))
    player: BackgroundProcess | None = None
    try:
        running.start("core", ["core"], running.base_port, env={"SKYDECK_RECORDINGS_DIR": str(folder)})
        player = BackgroundProcess(
            [sys.executable, "-m", "services.cli", "bag", "play", str(bag), "--loop"],
            name="bag play", cwd=REPO, env={**os.environ, "SKYDECK_CORE_URL": running.url, "PYTHONUNBUFFERED": "1"},
        )
        player.wait_for_line("playing", 30)
        yield running, folder, player
    finally:
        if player is not None:
            player.stop(signal.SIGINT)
        running.stop()


@pytest.fixture
def page(recordings, browser) -> Iterator[tuple[object, Recorder]]:  # type: ignore[no-untyped-def]
    system, _, _ = recordings
    # Ready once main.js has set window.skydeck (after config.js's top-level await, which can be
    # after the load event): a test's predicate on window.skydeck.pose before then throws.
    with open_dashboard(browser, system.url, "window.skydeck !== undefined") as opened:
        yield opened


def test_the_views_follow_a_recording_being_played(page) -> None:  # type: ignore[no-untyped-def]
    tab, seen = page
    tab.wait_for_function("window.skydeck.pose !== null && window.skydeck.track.length > 10", timeout=20_000)
    first = tab.evaluate("window.skydeck.pose")
    assert first["z"] == pytest.approx(3.0) and math.hypot(first["x"], first["y"]) == pytest.approx(5.0, abs=1e-6)
    tab.wait_for_function(f"Math.abs(window.skydeck.pose.x - {first['x']}) > 0.5", timeout=10_000)  # it moves
    assert tab.evaluate("window.skydeck.mapFrames") > 0
    nodes = tab.evaluate("window.skydeck.graph.nodes.map((n) => n.name)")
    assert any(name.startswith("/bag_play_") for name in nodes)  # the player is a node in the graph
    assert not seen.errors, seen.errors


def test_the_recorder_panel_records_lists_and_serves_the_file(page, recordings) -> None:  # type: ignore[no-untyped-def]
    tab, seen = page
    _, folder, _ = recordings
    tab.wait_for_function("window.skydeck.recorder.current !== null", timeout=10_000)
    assert tab.get_attribute("#record-toggle", "aria-pressed") == "false"
    tab.click("#record-toggle")
    tab.wait_for_function(
        "window.skydeck.recorder.recording && (window.skydeck.recorder.current.topics['/drone/pose'] || 0) > 30",
        timeout=20_000,
    )
    assert tab.get_attribute("#record-toggle", "aria-pressed") == "true"
    assert "recording skydeck_" in tab.inner_text("#record-status")
    tab.click("#record-toggle")
    tab.wait_for_function("!window.skydeck.recorder.recording && window.skydeck.recorder.files.length > 0", timeout=20_000)
    name = tab.evaluate("window.skydeck.recorder.current.name")
    link = tab.locator(f"#recording-list li[data-recording='{name}'] a")
    href = link.get_attribute("href")
    assert link.get_attribute("download") == name and href == f"/api/recordings/{name}"
    body = tab.request.get(tab.url.rstrip("/") + href).body()
    assert body.startswith(MAGIC) and body == (folder / name).read_bytes()
    with BagReader(folder / name) as bag:
        assert not bag.summary.recovered and bag.summary.topic("/drone/pose").count > 30
        assert bag.summary.topic("/simulator/camera") is None
    assert not seen.errors, seen.errors
