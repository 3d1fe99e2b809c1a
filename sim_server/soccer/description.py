"""The soccer room as its clients see it before it runs (``GET /api/config``'s ``worlds.soccer``):
the robot world's numbers and names (it ``extends`` that world), the ball's and the cameras'.
Pure constants: importing this loads no PyBullet."""

from __future__ import annotations

from sim_server.description import WorldDescription
from sim_server.robot.description import DESCRIPTION as ROBOT
from sim_server.soccer import limits

__all__ = ["DESCRIPTION"]

DESCRIPTION = WorldDescription(
    constants={
        **ROBOT.constants,
        "ball_radius_m": limits.BALL_RADIUS_M,
        "ball_start_xy_m": list(limits.BALL_START_M),
        "camera_vertical_fov_deg": limits.CAMERA_VERTICAL_FOV_DEG,
    },
    topics={
        **ROBOT.topics,
        # per robot
        "camera_image": "camera/image_raw",
        "camera_info": "camera/camera_info",
        # the room's
        "balls": "/simulator/balls",
    },
    services=dict(ROBOT.services),
    extends="robot",
)
