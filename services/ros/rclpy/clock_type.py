"""``rclpy.clock_type.ClockType``: which clock a time was read on."""

from __future__ import annotations

from enum import IntEnum

__all__ = ["ClockType"]


class ClockType(IntEnum):
    """ROS_TIME follows /clock when ``use_sim_time`` is set; SYSTEM_TIME and STEADY_TIME never do."""

    UNINITIALIZED = 0
    ROS_TIME = 1
    SYSTEM_TIME = 2
    STEADY_TIME = 3
