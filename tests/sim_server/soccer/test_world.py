"""The soccer room in PyBullet, in this process: the ball rests where it starts, a robot pushes
it with its wheel motors alone (the ball moves only by contact), it rolls to rest, a reset puts
it back; each robot's camera sees it where its CameraInfo says a pinhole would, and the camera's
frame on /tf_static points where the camera looks."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from shared_models.std_msgs import Header
from sim_server.camera import render_rgb
from sim_server.robot.world import RobotWorldConfig
from sim_server.soccer.cameras import camera_info, camera_view
from sim_server.soccer.limits import (
    BALL_RADIUS_M,
    BALL_START_M,
    CAMERA_FORWARD_M,
    CAMERA_HEIGHT_M,
    CAMERA_PITCH_DEG,
)
from sim_server.soccer.node import _pitched_optical
from sim_server.soccer.world import SoccerWorld

pytestmark = pytest.mark.timeout(60)


@pytest.fixture
def world() -> Iterator[SoccerWorld]:
    with SoccerWorld(RobotWorldConfig(seed=1)) as built:
        yield built


def _drive_at_ball(world: SoccerWorld, seconds: float) -> None:
    """Steer robot 0 at the ball (the truth), 0.3 m/s, re-sent at 10 Hz as a node would."""
    for _ in range(int(seconds * 10)):
        x, y, yaw = world.robot_pose(0)
        bx, by = world.ball_position()
        bearing = math.remainder(math.atan2(by - y, bx - x) - yaw, math.tau)
        world.set_cmd_vel(0, 0.3, 1.5 * bearing)
        world.step(world.PHYSICS_HZ // 10)


def test_the_ball_rests_on_its_spot_until_something_touches_it(world: SoccerWorld) -> None:
    world.step(2 * world.PHYSICS_HZ)
    assert world.ball_position() == pytest.approx(BALL_START_M, abs=1e-4)
    assert world.ball_speed() < 1e-3


def test_a_robot_pushes_the_ball_with_its_motors_and_the_ball_rolls_to_rest(world: SoccerWorld) -> None:
    start_gap = math.dist(world.robot_pose(0)[:2], BALL_START_M)
    _drive_at_ball(world, 6.0)
    bx, by = world.ball_position()
    assert bx > BALL_START_M[0] + 0.5  # pushed along +x, the way the robot drives
    assert math.dist(world.robot_pose(0)[:2], (bx, by)) < start_gap
    assert world.robot_tilt_deg(0) < 2.0  # pushed, not climbed
    world.set_cmd_vel(0, 0.0, 0.0)
    world.step(10 * world.PHYSICS_HZ)
    assert world.ball_speed() < 0.01  # rolling friction and damping bring it to rest...
    x, y = world.ball_position()
    assert abs(x) < 4.0 - BALL_RADIUS_M + 0.01 and abs(y) < 4.0  # ...inside the walls


def test_a_reset_puts_the_ball_back_with_the_robots(world: SoccerWorld) -> None:
    _drive_at_ball(world, 6.0)
    assert math.dist(world.ball_position(), BALL_START_M) > 0.5
    world.reset()
    assert world.ball_position() == pytest.approx(BALL_START_M, abs=1e-6)
    assert world.robot_pose(0)[:2] == pytest.approx((0.0, 0.0), abs=1e-3)


def test_the_camera_sees_the_ball_where_its_camera_info_projects_it(world: SoccerWorld) -> None:
    width, height = 320, 240
    pixels = render_rgb(world.client, camera_view(*world.robot_pose(0)), width, height)
    rgb = np.frombuffer(pixels, np.uint8).reshape(height, width, 3).astype(int)
    ball = (rgb[:, :, 0] > 40) & (rgb[:, :, 0] > 2.5 * rgb[:, :, 1]) & (rgb[:, :, 0] > 2.5 * rgb[:, :, 2])  # its red-orange, lit or shaded
    assert ball.sum() > 200
    ys, xs = np.nonzero(ball)
    # The ball's centre in the camera's optical frame (z ahead, x right, y down), pitched down.
    pitch = math.radians(CAMERA_PITCH_DEG)
    dx, dy, dz = BALL_START_M[0] - CAMERA_FORWARD_M, BALL_START_M[1], BALL_RADIUS_M - CAMERA_HEIGHT_M
    ahead = dx * math.cos(pitch) - dz * math.sin(pitch)
    right = -dy
    down = -dx * math.sin(pitch) - dz * math.cos(pitch)
    k = camera_info(Header(), width, height).k
    u, v = k[0] * right / ahead + k[2], k[4] * down / ahead + k[5]
    assert (xs.mean(), ys.mean()) == pytest.approx((u, v), abs=1.5)


def test_the_camera_frame_looks_ahead_and_down() -> None:
    q = _pitched_optical()
    x, y, z, w = q.x, q.y, q.z, q.w

    def rotate(v: tuple[float, float, float]) -> tuple[float, float, float]:
        matrix = (
            (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
            (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
            (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)),
        )
        return tuple(sum(row[i] * v[i] for i in range(3)) for row in matrix)  # type: ignore[return-value]

    pitch = math.radians(CAMERA_PITCH_DEG)
    assert rotate((0, 0, 1)) == pytest.approx((math.cos(pitch), 0, -math.sin(pitch)))  # optical z: ahead, down
    assert rotate((1, 0, 0)) == pytest.approx((0, -1, 0))  # optical x: the robot's right
    assert math.isclose(x * x + y * y + z * z + w * w, 1.0)
