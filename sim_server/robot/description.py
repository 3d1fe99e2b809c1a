"""The robot world as its clients see it before it runs (``GET /api/config``'s ``worlds.robot``):
the room's and the Neato's numbers, and the names of its topics (a relative name is one per
robot, under each namespace ``/simulator/world`` lists). Pure constants: importing this loads no
PyBullet."""

from __future__ import annotations

from sim_server.description import WorldDescription
from sim_server.robot import limits

__all__ = ["DESCRIPTION"]

DESCRIPTION = WorldDescription(
    constants={
        "room_half_size_m": limits.ROOM_HALF_SIZE_M,
        "wall_thickness_m": limits.WALL_THICKNESS_M,
        "robot_radius_m": limits.ROBOT_RADIUS_M,
        "wheel_separation_m": limits.WHEEL_SEPARATION_M,
        "leg_radius_m": limits.LEG_RADIUS_M,
        "leg_spacing_m": limits.LEG_SPACING_M,
        "max_linear_speed": limits.MAX_LINEAR_SPEED,
        "max_angular_speed": limits.MAX_ANGULAR_SPEED,
        "range_max_m": limits.RANGE_MAX_M,
        "starts_xy_m": [list(start) for start in limits.ROBOT_STARTS_M],
    },
    topics={
        # per robot
        "odom": "odom",
        "scan": "scan",
        "bump": "bump",
        "cmd_vel": "cmd_vel",
        # the room's
        "tf": "/tf",
        "tf_static": "/tf_static",
        "robots": "/simulator/robots",
        "people": "/simulator/people",
        "obstacles": "/simulator/obstacles",
    },
)
