"""The 3D view in the real robot world (``skydeck run sim --world robot``): the issue's own test.

Add ``/scan`` by topic and see the beam straight ahead end at the +x wall (the robot starts at
the origin facing +x, and the corridor to that wall stays clear); switch the fixed frame from
``odom`` to ``base_link`` and see every point of a scan where its range puts it from the robot,
the robot at the origin. The points are read back from the scene and matched, by stamp, with the
scans this test reads from ``/scan`` itself.
"""

from __future__ import annotations

import json
import math
import threading
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from websockets.sync.client import connect

from shared_models.geometry_msgs import Twist, Vector3
from tests.conftest import free_port_block
from tests.web_ui.camera_projection import (
    FOLLOWED_MODEL_PX,
    MIN_FILLED,
    MIN_MODEL_PX,
    MIN_SPAN,
    Camera,
    measure_world,
    report,
)
from tests.web_ui.conftest import open_dashboard
from tests.web_ui.system import System
from tests.web_ui.threaded_node import ThreadedNode
from tests.web_ui.view3d_page import (
    add_by_topic,
    follow_and_zoom,
    open_3d,
    screenshot_path,
    view,
    wait_display,
    wait_view,
)

pytest.importorskip("sim_server.robot", reason="the robot world (issue 14) is not in this tree")

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def system() -> Iterator[System]:
    """The core and the simulator in the robot world."""
    base = free_port_block(5)
    running = System(base)
    try:
        running.start("core", ["core"], base)
        running.start("sim", ["run", "sim", "--world", "robot", "--seed", "1", "--speed", "1"], base + 1)
        yield running
    finally:
        running.stop()


@pytest.fixture(scope="module")
def room(system: System) -> dict[str, float]:
    import urllib.request

    with urllib.request.urlopen(system.url + "/api/config", timeout=5) as reply:
        return json.loads(reply.read())["worlds"]["robot"]  # type: ignore[no-any-return]


@pytest.fixture
def scans(system: System) -> Iterator[Callable[[float], dict[str, object] | None]]:
    """The /scan messages of the last seconds, read as any client would: ``scans(stamp)`` is the
    one taken at ``stamp`` (seconds), waited for a while (this reader can be behind the page's),
    or None."""
    received: dict[float, dict[str, object]] = {}
    arrived = threading.Condition()  # guards `received`, told of each message
    stop = threading.Event()

    def read() -> None:
        with connect(f"{system.ws_url}/scan") as websocket:
            while not stop.is_set():
                try:
                    msg = json.loads(websocket.recv(timeout=0.5))
                except TimeoutError:
                    continue
                stamp = msg["header"]["stamp"]
                with arrived:
                    received[stamp["sec"] + stamp["nanosec"] * 1e-9] = msg
                    while len(received) > 100:
                        received.pop(next(iter(received)))
                    arrived.notify_all()

    def taken_at(stamp: float) -> dict[str, object] | None:
        def match() -> dict[str, object] | None:
            return next((msg for t, msg in received.items() if abs(t - stamp) < 1e-6), None)

        with arrived:
            return arrived.wait_for(match, timeout=10)

    thread = threading.Thread(target=read, daemon=True)
    thread.start()
    with arrived:  # read from before the page draws the scans matched with these
        assert arrived.wait_for(lambda: received, timeout=20), "no /scan for the test to read"
    yield taken_at
    stop.set()
    thread.join(timeout=5)


@pytest.fixture
def dashboard(system: System, browser: object) -> Iterator[tuple[object, object]]:
    with open_dashboard(browser, system.url, "window.skydeck !== undefined") as (page, recorder):
        open_3d(page)
        # All four frames: with /tf in before /tf_static, the default fixed frame is odom for a while.
        wait_view(
            page,
            "v.frames.length >= 4 && v.world.robot.present && v.world.robot.obstacles.length >= 4",
        )
        yield page, recorder


def beam_points(msg: dict[str, object], laser_z: float) -> list[list[float]]:
    """Where a scan's returns are in base_link: polar (range, angle) at the laser's height."""
    points = []
    for i, r in enumerate(msg["ranges"]):  # type: ignore[arg-type]
        if r and msg["range_min"] <= r <= msg["range_max"]:  # type: ignore[operator]
            angle = msg["angle_min"] + i * msg["angle_increment"]  # type: ignore[operator]
            points.append([r * math.cos(angle), r * math.sin(angle), laser_z])
    return points


def test_scan_by_topic_reaches_the_wall_then_rides_with_the_robot(dashboard, scans, room) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    assert view(page)["fixedFrame"] == "map"
    add_by_topic(page, "/scan")
    scan = wait_display(page, "/scan", "d.stamp !== null && d.points.length > 100")
    ahead = [p for p in scan["points"] if p[0] > 0 and abs(p[1]) < 0.05]
    assert ahead, "a return straight ahead"
    wall = room["room_half_size_m"]
    assert abs(max(p[0] for p in ahead) - wall) < 0.03, "the beam ahead ends at the +x wall"
    page.select_option("#view3d-fixed-frame", "odom")
    wait_display(page, "/scan", f"v.fixedFrame === 'odom' && d.stamp > {scan['stamp']}")
    page.select_option("#view3d-fixed-frame", "base_link")
    stamp = scan["stamp"]
    for _ in range(2):
        drawn = wait_display(page, "/scan", f"v.fixedFrame === 'base_link' && d.stamp > {stamp}")
        stamp = drawn["stamp"]
        v = view(page)
        assert v["world"]["robot"]["robot"] == [0, 0, 0], "in base_link the robot is at the origin"
        laser_z = v["world"]["robot"]["laser"][2]
        published = scans(stamp)
        assert published is not None, "the drawn scan is one the simulator published"
        expected = beam_points(published, laser_z)
        assert len(drawn["points"]) == len(expected)
        worst = max(math.dist(a, b) for a, b in zip(drawn["points"], expected, strict=True))
        assert worst < 2e-3, f"a point is {worst:.4f} m from where its range puts it"
    assert recorder.errors == []


def test_screenshot_of_the_robot_world_in_3d(dashboard, system: System, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    """The docs' picture (docs/img/view3d_robot.png with SKYDECK_UPDATE_SCREENSHOTS=1): the room,
    the robot driven on an arc, its scan, odometry trail and frames."""
    page, recorder = dashboard
    page.set_viewport_size({"width": 1600, "height": 1100})
    node = ThreadedNode("view3d_driver", system.url)
    node.publish_every("/cmd_vel", lambda: Twist(linear=Vector3(x=0.25), angular=Vector3(z=0.5)), 0.1)
    try:
        add_by_topic(page, "/scan")
        add_by_topic(page, "/odom", color="#ff5fd2")
        add_by_topic(page, "/tf")
        wait_display(page, "/odom", "d.trail > 60")
    finally:
        node.close()
    follow_and_zoom(page, -9, "v.world.robot.robot")
    screenshot = screenshot_path("view3d_robot.png", tmp_path)
    page.locator("#map-panel").screenshot(path=str(screenshot))
    assert screenshot.stat().st_size > 10_000
    assert recorder.errors == []


def test_the_robot_world_opens_framed_with_the_robot_visible(browser, system: System, room: dict[str, float]) -> None:  # type: ignore[no-untyped-def]
    """The room fills the canvas at open, the robot is drawn at a visible size, Follow brings
    the camera close (measured as test_view3d_framing.py measures the drone world)."""
    with open_dashboard(browser, system.url, "window.skydeck && window.skydeck.view3d !== undefined") as (page, recorder):
        open_3d(page)
        v = wait_view(page, "v.camera.world === 'robot' && v.world.robot.robots.some((r) => r.position)")
        camera = Camera(v["camera"])
        figures = measure_world(camera, room["room_half_size_m"] + room["wall_thickness_m"], 0.5)
        robot = v["world"]["robot"]["robots"][0]
        assert camera.inside(camera.pixel(robot["position"]))
        figures["robot_px"] = camera.span_px(robot["position"], 2 * room["robot_radius_m"] * robot["scale"])
        report("robot world", figures)
        assert figures["filled"] >= MIN_FILLED and max(figures["span_x"], figures["span_y"]) >= MIN_SPAN, figures
        assert figures["robot_px"] >= MIN_MODEL_PX, figures
        page.click("#view3d-follow")
        v = wait_view(page, "v.camera.follow && Math.hypot(...v.camera.position.map((p, i) => p - v.camera.target[i])) < 2.6")
        robot = v["world"]["robot"]["robots"][0]
        followed = Camera(v["camera"]).span_px(robot["position"], 2 * room["robot_radius_m"] * robot["scale"])
        print(f"3D view, Follow: the robot {followed:.0f} px across, at scale {robot['scale']}")
        assert robot["scale"] == 1 and followed >= FOLLOWED_MODEL_PX
        # A reload keeps the view the user left (the room's), it does not frame it again.
        box = page.locator("#view3d-canvas").bounding_box()
        page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        page.mouse.wheel(0, -300)
        page.wait_for_function("JSON.parse(localStorage.getItem('skydeck.view3d') || '{}').camera?.world === 'robot'")
        page.wait_for_function(
            "JSON.parse(localStorage.getItem('skydeck.view3d')).camera.position.every((p, i) => Math.abs(p - window.skydeck.view3d().camera.position[i]) < 1e-6)"
        )
        before = view(page)["camera"]
        page.reload()
        open_3d(page)
        after = wait_view(page, "v.world.robot.robots.some((r) => r.position)")["camera"]
        assert math.dist(after["position"], before["position"]) < 1e-6
    assert recorder.errors == []
