"""What the robot world's criteria share: the start, the gap to the nearest wall or obstacle, and
which side of the robot a wall is on."""

from __future__ import annotations

import math
from collections.abc import Sequence

from services.grading.geometry import distance_to_box
from services.grading.shapes import Box, Pose
from sim_server.robot.limits import ROBOT_RADIUS_M

__all__ = ["ROBOT_RADIUS_M", "gap", "nearest_wall", "start_of"]


def start_of(track: Sequence[Pose]) -> Pose:
    """The robot's first pose (ValueError for a run with none)."""
    if not track:
        raise ValueError("the run recorded no robot pose (/simulator/robots)")
    return track[0]


def gap(pose: Pose, boxes: Sequence[Box]) -> float:
    """Metres between the robot's body and the nearest of ``boxes`` (negative: overlapping)."""
    if not boxes:
        return math.inf
    return min(distance_to_box(pose.x, pose.y, box) for box in boxes) - ROBOT_RADIUS_M


def nearest_wall(pose: Pose, walls: Sequence[Box]) -> tuple[float, float]:
    """Distance (m) from the robot's centre to the nearest wall, and the bearing of the wall's
    nearest point (rad, counter-clockwise from the robot's heading: negative on its right)."""
    best = (math.inf, 0.0)
    for wall in walls:
        c, s = math.cos(wall.yaw), math.sin(wall.yaw)
        dx, dy = pose.x - wall.x, pose.y - wall.y
        lx = max(-wall.size_x / 2, min(wall.size_x / 2, c * dx + s * dy))
        ly = max(-wall.size_y / 2, min(wall.size_y / 2, -s * dx + c * dy))
        px, py = wall.x + c * lx - s * ly, wall.y + s * lx + c * ly
        distance = math.hypot(px - pose.x, py - pose.y)
        if distance < best[0]:
            bearing = math.remainder(math.atan2(py - pose.y, px - pose.x) - pose.yaw, math.tau)
            best = (distance, bearing)
    return best
