"""The 3D view opens framed on the world, in both worlds: how much of the canvas the world fills
at open, how many pixels the drone or the robot spans, and Follow bringing the camera close.

Measured independently of the page's code: the camera (position, target, field of view, canvas
size) is read from ``window.skydeck.view3d()`` and the world's corners (from ``/api/config``) and
the model (where the view draws it, at the scale it says it draws it) are projected here, with
the pinhole model three.js's perspective camera uses. The figures are printed (docs/view3d.md).
"""

from __future__ import annotations

import json
import math
import urllib.request
from collections.abc import Iterator
from typing import Any

import pytest

from tests.conftest import free_port_block
from tests.web_ui.conftest import open_dashboard
from tests.web_ui.system import System
from tests.web_ui.view3d_page import open_3d, view, wait_view

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]

READY = "window.skydeck && window.skydeck.view3d !== undefined"
DRONE_SPAN_M = 0.55 + 0.24  # motor to motor, plus a rotor
ARENA_HEIGHT_M = 3.0  # the drone world is framed up to this height (a flying drone, the boxes)
WALL_HEIGHT_M = 0.5
MIN_FILLED = 0.3  # of the canvas's area: a square floor seen at 45 degrees is a diamond, half its box
MIN_SPAN = 0.85  # of the canvas's width or height, spanned by the world
MIN_MODEL_PX = 36  # the drone or robot at open
FOLLOWED_MODEL_PX = 60  # after Follow, at true size


class Camera:
    """three.js's perspective camera as the snapshot gives it: z up, looking at the target."""

    def __init__(self, snapshot: dict[str, Any]) -> None:
        self.position = snapshot["position"]
        target = snapshot["target"]
        self.width, self.height = snapshot["canvas"]
        self.tan = math.tan(math.radians(snapshot["fov"]) / 2)
        self.forward = _unit(_sub(target, self.position))
        self.right = _unit(_cross(self.forward, [0.0, 0.0, 1.0]))
        self.up = _cross(self.right, self.forward)

    def pixel(self, point: list[float]) -> tuple[float, float]:
        """Where ``point`` is drawn on the canvas (pixels from its top left)."""
        d = _sub(point, self.position)
        depth = _dot(d, self.forward)
        if depth <= 0:
            raise AssertionError(f"{point} is behind the camera")
        x = _dot(d, self.right) / (depth * self.tan * self.width / self.height)
        y = _dot(d, self.up) / (depth * self.tan)
        return (x + 1) / 2 * self.width, (1 - y) / 2 * self.height

    def inside(self, pixel: tuple[float, float]) -> bool:
        return 0 <= pixel[0] <= self.width and 0 <= pixel[1] <= self.height

    def span_px(self, point: list[float], metres: float) -> float:
        """How many pixels ``metres`` across the screen at ``point`` spans."""
        half = [c * metres / 2 for c in self.right]
        (x0, y0), (x1, y1) = self.pixel(_sub(point, half)), self.pixel([p + h for p, h in zip(point, half, strict=True)])
        return math.hypot(x1 - x0, y1 - y0)


def _sub(a: list[float], b: list[float]) -> list[float]:
    return [x - y for x, y in zip(a, b, strict=True)]


def _dot(a: list[float], b: list[float]) -> float:
    return sum(x * y for x, y in zip(a, b, strict=True))


def _cross(a: list[float], b: list[float]) -> list[float]:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _unit(a: list[float]) -> list[float]:
    length = math.sqrt(_dot(a, a))
    return [x / length for x in a]


def _hull_area(points: list[tuple[float, float]]) -> float:
    hull: list[tuple[float, float]] = []
    for p in sorted(points) + sorted(points)[::-1][1:]:  # monotone chain, both halves
        while len(hull) >= 2 and (hull[-1][0] - hull[-2][0]) * (p[1] - hull[-2][1]) - (hull[-1][1] - hull[-2][1]) * (p[0] - hull[-2][0]) <= 0:
            hull.pop()
        hull.append(p)
    return abs(sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(hull, hull[1:] + hull[:1], strict=True))) / 2


def measure_world(camera: Camera, half: float, height: float) -> dict[str, float]:
    """What the world's box (a square floor of half-size ``half``, ``height`` tall) covers."""
    corners = [camera.pixel([x, y, z]) for x in (-half, half) for y in (-half, half) for z in (0.0, height)]
    assert all(camera.inside(c) for c in corners), f"part of the world is off the canvas: {corners}"
    xs, ys = [c[0] for c in corners], [c[1] for c in corners]
    return {
        "filled": _hull_area(corners) / (camera.width * camera.height),
        "span_x": (max(xs) - min(xs)) / camera.width,
        "span_y": (max(ys) - min(ys)) / camera.height,
    }


def _config(system: System) -> dict[str, Any]:
    with urllib.request.urlopen(system.url + "/api/config", timeout=5) as reply:
        return json.loads(reply.read())["worlds"]  # type: ignore[no-any-return]


def _report(world: str, figures: dict[str, float]) -> None:
    print(f"\n3D view at open, {world}: " + ", ".join(f"{k} {v:.2f}" for k, v in figures.items()))


def test_the_drone_world_opens_framed_with_the_drone_visible(browser, system: System) -> None:  # type: ignore[no-untyped-def]
    arena = _config(system)["drone"]
    with open_dashboard(browser, system.url, READY) as (page, recorder):
        open_3d(page)
        v = wait_view(page, "v.camera.world === 'drone' && v.world.drone.drone !== null && v.world.drone.droneScale > 0")
        camera = Camera(v["camera"])
        figures = measure_world(camera, arena["arena_half_size_m"], ARENA_HEIGHT_M)
        drone = v["world"]["drone"]["drone"]
        assert camera.inside(camera.pixel(drone)), "the drone is in view"
        figures["drone_px"] = camera.span_px(drone, DRONE_SPAN_M * v["world"]["drone"]["droneScale"])
        _report("drone world", figures)
        assert figures["filled"] >= MIN_FILLED and max(figures["span_x"], figures["span_y"]) >= MIN_SPAN, figures
        assert figures["drone_px"] >= MIN_MODEL_PX, figures
        page.click("#view3d-follow")
        v = wait_view(
            page,
            "v.camera.follow && Math.hypot(...v.camera.position.map((p, i) => p - v.camera.target[i])) < 5.5"
            " && Math.hypot(...v.camera.target.map((t, i) => t - v.world.drone.drone[i])) < 0.3",
        )
        camera = Camera(v["camera"])
        drone = v["world"]["drone"]["drone"]
        followed = camera.span_px(drone, DRONE_SPAN_M * v["world"]["drone"]["droneScale"])
        print(f"3D view, Follow: the drone {followed:.0f} px across, at scale {v['world']['drone']['droneScale']}")
        assert v["world"]["drone"]["droneScale"] == 1 and followed >= FOLLOWED_MODEL_PX
        assert abs(camera.pixel(drone)[0] - camera.width / 2) < 2 and abs(camera.pixel(drone)[1] - camera.height / 2) < 2
        page.click("#view3d-reset")  # Reset view frames the world again
        v = wait_view(page, "!v.camera.follow || true")
        assert measure_world(Camera(v["camera"]), arena["arena_half_size_m"], ARENA_HEIGHT_M)["filled"] >= MIN_FILLED
    assert recorder.errors == []


@pytest.fixture(scope="module")
def room_system() -> Iterator[System]:
    """The core and the simulator in the robot world."""
    base = free_port_block(2)
    running = System(base)
    try:
        running.start("core", ["core"], base)
        running.start("sim", ["run", "sim", "--world", "robot", "--seed", "1", "--speed", "1"], base + 1)
        yield running
    finally:
        running.stop()


def test_the_robot_world_opens_framed_with_the_robot_visible(browser, room_system: System) -> None:  # type: ignore[no-untyped-def]
    room = _config(room_system)["robot"]
    with open_dashboard(browser, room_system.url, READY) as (page, recorder):
        open_3d(page)
        v = wait_view(page, "v.camera.world === 'robot' && v.world.robot.robots.some((r) => r.position)")
        camera = Camera(v["camera"])
        figures = measure_world(camera, room["room_half_size_m"] + room["wall_thickness_m"], WALL_HEIGHT_M)
        robot = v["world"]["robot"]["robots"][0]
        assert camera.inside(camera.pixel(robot["position"]))
        figures["robot_px"] = camera.span_px(robot["position"], 2 * room["robot_radius_m"] * robot["scale"])
        _report("robot world", figures)
        assert figures["filled"] >= MIN_FILLED and max(figures["span_x"], figures["span_y"]) >= MIN_SPAN, figures
        assert figures["robot_px"] >= MIN_MODEL_PX, figures
        page.click("#view3d-follow")
        v = wait_view(page, "v.camera.follow && Math.hypot(...v.camera.position.map((p, i) => p - v.camera.target[i])) < 2.6")
        robot = v["world"]["robot"]["robots"][0]
        followed = Camera(v["camera"]).span_px(robot["position"], 2 * room["robot_radius_m"] * robot["scale"])
        print(f"3D view, Follow: the robot {followed:.0f} px across, at scale {robot['scale']}")
        assert robot["scale"] == 1 and followed >= FOLLOWED_MODEL_PX
        # A reload keeps the view the user left (the room's), it does not frame it again.
        page.mouse.move(*_canvas_centre(page))
        page.mouse.wheel(0, -300)
        page.wait_for_function("JSON.parse(localStorage.getItem('skydeck.view3d') || '{}').camera?.world === 'robot'")
        before = view(page)["camera"]
        page.wait_for_function(
            "JSON.parse(localStorage.getItem('skydeck.view3d')).camera.position.every((p, i) => Math.abs(p - window.skydeck.view3d().camera.position[i]) < 1e-6)"
        )
        before = view(page)["camera"]
        page.reload()
        open_3d(page)
        after = wait_view(page, "v.world.robot.robots.some((r) => r.position)")["camera"]
        assert math.dist(after["position"], before["position"]) < 1e-6
    assert recorder.errors == []


def _canvas_centre(page) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    box = page.locator("#view3d-canvas").bounding_box()
    return box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
