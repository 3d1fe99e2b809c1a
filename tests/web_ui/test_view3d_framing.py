"""The 3D view opens framed on the world: how much of the canvas the drone world fills at open,
how many pixels the drone spans, and Follow bringing the camera close (the robot world's twin is
in test_view3d_robot_world.py).

Measured independently of the page's code: the camera (position, target, field of view, canvas
size) is read from ``window.skydeck.view3d()`` and the world's corners (from ``/api/config``) and
the model (where the view draws it, at the scale it says it draws it) are projected here
(``camera_projection.py``). The figures are printed (docs/view3d.md).
"""

from __future__ import annotations

import json
import urllib.request
from typing import Any

import pytest

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
from tests.web_ui.view3d_page import open_3d, wait_view

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]

READY = "window.skydeck && window.skydeck.view3d !== undefined"
DRONE_SPAN_M = 0.55 + 0.24  # motor to motor, plus a rotor
ARENA_HEIGHT_M = 3.0  # the drone world is framed up to this height (a flying drone, the boxes)


def _config(system: System) -> dict[str, Any]:
    with urllib.request.urlopen(system.url + "/api/config", timeout=5) as reply:
        return json.loads(reply.read())["worlds"]  # type: ignore[no-any-return]


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
        report("drone world", figures)
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
