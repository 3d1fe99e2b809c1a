"""The camera drawn with OpenGL: aligned with the world (its shapes where PyBullet's own
renderer and the projection of the bodies' positions put them), the same bytes for the same
state, fast enough to be the default, and PyBullet's renderer, said once, where OpenGL is not."""

from __future__ import annotations

import logging
from collections.abc import Iterator

import numpy as np
import pybullet as p
import pytest

import sim_server.camera as camera
import sim_server.camera_gl as camera_gl
from sim_server.camera import View, opengl_status, render_rgb
from sim_server.camera_gl import GlUnavailable, open_renderer
from sim_server.drone.camera import chase_view
from sim_server.drone.world import World, WorldConfig
from sim_server.robot.world import RobotWorld, RobotWorldConfig

pytestmark = pytest.mark.timeout(60)

WIDTH, HEIGHT = 320, 240
WHY_NOT = opengl_status()
needs_opengl = pytest.mark.skipif(WHY_NOT is not None, reason=f"no OpenGL here ({WHY_NOT}): `make test-deps` installs it")


@pytest.fixture(scope="module")
def drone_world() -> Iterator[World]:
    with World(WorldConfig(seed=1, boxes=8)) as world:
        world.step(480)  # the boxes have landed
        yield world


def _image(pixels: bytes) -> np.ndarray:
    return np.frombuffer(pixels, dtype=np.uint8).reshape(HEIGHT, WIDTH, 3).astype(int)


def _things(image: np.ndarray, ground: tuple[int, int]) -> np.ndarray:
    """Pixels of neither the sky (white) nor the ground (the colour at ``ground``, shading aside)."""
    floor = image[ground]
    sky = (image > 240).all(axis=2)
    return ~sky & (np.abs(image - floor).sum(axis=2) > 40)


def _project(view: View, point: tuple[float, float, float]) -> tuple[int, int]:
    """Where ``point`` appears (row, column), by PyBullet's own matrices."""
    view_matrix = np.array(p.computeViewMatrix(view.eye, view.target, (0, 0, 1))).reshape(4, 4).T
    projection = np.array(p.computeProjectionMatrixFOV(60.0, WIDTH / HEIGHT, view.near_m, view.far_m)).reshape(4, 4).T
    x, y, _, w = projection @ view_matrix @ np.array([*point, 1.0])
    return int((1 - (y / w + 1) / 2) * HEIGHT), int((x / w + 1) / 2 * WIDTH)


@needs_opengl
def test_the_boxes_appear_where_pybullets_renderer_and_the_projection_put_them(drone_world: World) -> None:
    view = View((-10.0, -14.0, 12.0), (3.0, 3.0, 0.0))
    ours = _image(render_rgb(drone_world.client, view, WIDTH, HEIGHT, renderer="opengl"))
    theirs = _image(render_rgb(drone_world.client, view, WIDTH, HEIGHT, renderer="pybullet"))
    mine, reference = _things(ours, (HEIGHT - 1, WIDTH // 2)), _things(theirs, (HEIGHT - 1, WIDTH // 2))
    overlap = (mine & reference).sum() / (mine | reference).sum()
    assert reference.sum() > 500 and overlap > 0.9, f"the shapes overlap {overlap:.2f}"
    for (x, y, z), _ in drone_world.boxes_poses():
        row, column = _project(view, (x, y, z))
        if 0 <= row < HEIGHT and 0 <= column < WIDTH:
            assert mine[row, column], f"box at ({x:.1f}, {y:.1f}) not drawn at its projection"


@needs_opengl
def test_the_robot_world_and_its_links_are_aligned_too() -> None:
    with RobotWorld(RobotWorldConfig(seed=1, robots=2)) as world:
        world.step(120)
        x, y, _ = world.robot_pose(0)
        view = View((x - 1.5, y - 1.0, 1.2), (x, y, 0.1), near_m=0.05, far_m=12.0)
        ours = _image(render_rgb(world.client, view, WIDTH, HEIGHT, renderer="opengl"))
        theirs = _image(render_rgb(world.client, view, WIDTH, HEIGHT, renderer="pybullet"))
        robot = _project(view, (x, y, 0.05))
    # The Neato is the dark one (its body, wheels and laser turret: a base and its links), in a
    # window around where it stands (the renderers shade the person and the boxes differently).
    row, column = robot
    window = (slice(max(row - 40, 0), row + 40), slice(max(column - 40, 0), column + 40))
    mine, reference = ours[window].sum(axis=2) < 200, theirs[window].sum(axis=2) < 200
    overlap = (mine & reference).sum() / (mine | reference).sum()
    assert reference.sum() > 300 and overlap > 0.85, f"the robots overlap {overlap:.2f}"
    assert ours[robot].sum() < 200, "the robot is drawn where it stands"


@needs_opengl
def test_the_same_state_draws_the_same_bytes(drone_world: World) -> None:
    view = chase_view(drone_world)
    first = render_rgb(drone_world.client, view, WIDTH, HEIGHT, renderer="opengl")
    assert render_rgb(drone_world.client, view, WIDTH, HEIGHT, renderer="opengl") == first
    other = open_renderer()  # another context draws the same
    try:
        matrices = (p.computeViewMatrix(view.eye, view.target, (0, 0, 1)),
                    p.computeProjectionMatrixFOV(60.0, WIDTH / HEIGHT, view.near_m, view.far_m))  # fmt: skip
        assert other.render(drone_world.client, *matrices, WIDTH, HEIGHT) == first
        assert len(other.render(drone_world.client, *matrices, 640, 480)) == 640 * 480 * 3
    finally:
        other.close()


def test_without_opengl_pybullets_renderer_says_so_once(
    drone_world: World, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    def unavailable() -> camera_gl.GlRenderer:
        raise GlUnavailable("no EGL OpenGL context (test): install libegl1 and libgl1-mesa-dri")

    monkeypatch.setattr(camera_gl, "open_renderer", unavailable)
    monkeypatch.setattr(camera._OpenGl, "renderer", None)
    monkeypatch.setattr(camera._OpenGl, "unavailable", None)
    view = chase_view(drone_world)
    with caplog.at_level(logging.WARNING, logger="sim_server.camera"):
        fallback = render_rgb(drone_world.client, view, WIDTH, HEIGHT)
        render_rgb(drone_world.client, view, WIDTH, HEIGHT)
    assert fallback == render_rgb(drone_world.client, view, WIDTH, HEIGHT, renderer="pybullet")
    notices = [r.getMessage() for r in caplog.records if r.name == "sim_server.camera"]
    assert len(notices) == 1 and "PyBullet's software renderer" in notices[0] and "libegl1" in notices[0]
    with pytest.raises(GlUnavailable, match="libegl1"):
        render_rgb(drone_world.client, view, WIDTH, HEIGHT, renderer="opengl")
