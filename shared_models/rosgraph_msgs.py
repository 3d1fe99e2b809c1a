"""rosgraph_msgs: Clock, the message type ROS 2 gives ``/clock``."""

from __future__ import annotations

from pydantic import Field

from shared_models._message import Message
from shared_models.builtin_interfaces import Time

__all__ = ["Clock"]


class Clock(Message):
    """The current simulated time, as a ROS 2 simulator publishes it on ``/clock``."""

    __ros_type__ = "rosgraph_msgs/msg/Clock"
    __ros_comment__ = (
        "# This message communicates the current time.\n"
        "#\n"
        "# For more information, see https://design.ros2.org/articles/clock_and_time.html"
    )

    clock: Time = Field(default_factory=Time)
