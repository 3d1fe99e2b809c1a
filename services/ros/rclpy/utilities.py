"""``rclpy.utilities``: ``ok``, ``remove_ros_args``, the default context."""

from __future__ import annotations

from services.ros.rclpy.context import Context, default_context

__all__ = ["get_default_context", "ok", "remove_ros_args"]


def get_default_context() -> Context:
    return default_context


def ok(*, context: Context | None = None) -> bool:
    """Whether rclpy is initialised and not shut down."""
    return (context or default_context).ok()


def remove_ros_args(args: list[str] | None = None) -> list[str]:
    """``args`` (default ``sys.argv``) without ``--ros-args ... [--]``, for the program's own parser."""
    import sys

    from services.runtime.ros_args import ROS_ARGS, split_ros_args

    args = list(sys.argv if args is None else args)
    return split_ros_args(args)[0] if ROS_ARGS in args else args
