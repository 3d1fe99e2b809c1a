"""ROS 1's time field names on what a rosbridge connection is sent, for ROS 1's own types.

Skydeck's messages carry ROS 2's ``{"sec", "nanosec"}``. ROS 1's actionlib (``actionlib_msgs``
and every ``XActionGoal``/``XActionFeedback``/``XActionResult`` around it) exists only in ROS 1,
and the clients that speak it read ROS 1's ``{"secs", "nsecs"}``: roslibpy's
``SimpleActionServer`` reads a cancel request's ``stamp["secs"]``. So a message of a type that
holds an ``actionlib_msgs`` type is sent with both names in each time (ROS 2's and ROS 1's),
which either kind of client reads; every other message is sent as it is. The choice is made once
per type; the rewrite is made once per frame, for every connection (:mod:`.frames`).
"""

from __future__ import annotations

import functools
import json
from typing import Any

from shared_models import Message
from shared_models.interfaces import field_types

__all__ = ["speaks_ros1", "with_ros1_times"]

_ROS1_ONLY_PACKAGE = "actionlib_msgs/"


@functools.cache
def speaks_ros1(cls: type[Message]) -> bool:
    """Whether ``cls`` is ROS 1's actionlib's, or holds one of its types."""
    if cls.__ros_type__.startswith(_ROS1_ONLY_PACKAGE):
        return True
    return any(nested is not None and speaks_ros1(nested) for _, _, nested in field_types(cls))


def with_ros1_times(frame: str) -> str:
    """``frame`` (a message's JSON) with ``secs``/``nsecs`` beside each ``sec``/``nanosec``."""

    def both(value: Any) -> Any:
        if isinstance(value, list):
            return [both(item) for item in value]
        if not isinstance(value, dict):
            return value
        out = {key: both(item) for key, item in value.items()}
        if "sec" in out and "nanosec" in out and len(out) == 2:
            out["secs"], out["nsecs"] = out["sec"], out["nanosec"]
        return out

    return json.dumps(both(json.loads(frame)), separators=(",", ":"))
