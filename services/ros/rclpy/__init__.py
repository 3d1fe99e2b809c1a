"""Skydeck's rclpy (ROS 2's Python client library): ``import rclpy`` in a file ``skydeck run`` runs.

    import rclpy
    from rclpy.node import Node

    def main(args=None):
        rclpy.init(args=args)
        node = SendMessageNode()
        rclpy.spin(node)
        rclpy.shutdown()

A thin façade over the SDK (:mod:`services.runtime`): a node here is an SDK node on the bridge's
event loop (:mod:`services.ros.bridge`), callbacks run in the executor that spins it. What it has
and where it differs from rclpy is in docs/ros.md.
"""

from __future__ import annotations

from typing import Any

from services.ros.errors import not_provided_attributes
from services.ros.rclpy import (
    callback_groups,
    clock,
    context,
    duration,
    executors,
    logging,
    node,
    parameter,
    qos,
    task,
    time,
)
from services.ros.rclpy.context import Context, default_context
from services.ros.rclpy.executors import Executor, get_global_executor
from services.ros.rclpy.node import Node
from services.ros.rclpy.task import Future
from services.ros.rclpy.utilities import get_default_context, ok, remove_ros_args

__all__ = [
    "callback_groups",
    "clock",
    "context",
    "create_node",
    "duration",
    "executors",
    "get_default_context",
    "get_global_executor",
    "init",
    "logging",
    "node",
    "ok",
    "parameter",
    "qos",
    "remove_ros_args",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "task",
    "time",
    "try_shutdown",
]


def init(*, args: list[str] | None = None, context: Context | None = None, domain_id: int | None = None,
         signal_handler_options: Any = None) -> None:  # fmt: skip
    """Start rclpy: ``args`` (default: the program's command line) may carry ``--ros-args``."""
    (context or default_context).init(args)


def shutdown(*, context: Context | None = None, uninstall_handlers: bool | None = None) -> None:
    """End rclpy: ``ok()`` is False, spins return, the process's nodes leave the graph."""
    (context or default_context).shutdown()


def try_shutdown(*, context: Context | None = None, uninstall_handlers: bool | None = None) -> None:
    shutdown(context=context)


def create_node(node_name: str, **kwargs: Any) -> Node:
    """``rclpy.create_node('talker')``: a Node (rclpy's keywords accepted)."""
    return Node(node_name, **kwargs)


def spin(node: Node, executor: Executor | None = None) -> None:
    """Run ``node``'s callbacks until rclpy shuts down or the node is destroyed."""
    executor = executor or get_global_executor()
    executor.add_node(node)
    try:
        executor.spin()
    finally:
        executor.remove_node(node)


def spin_once(node: Node, *, executor: Executor | None = None, timeout_sec: float | None = None) -> None:
    """Run at most one callback of ``node``, waiting up to ``timeout_sec`` for one."""
    executor = executor or get_global_executor()
    executor.add_node(node)
    try:
        executor.spin_once(timeout_sec=timeout_sec)
    finally:
        executor.remove_node(node)


def spin_until_future_complete(
    node: Node, future: Future, executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    """Run ``node``'s callbacks until ``future`` is done (or ``timeout_sec`` passes)."""
    executor = executor or get_global_executor()
    executor.add_node(node)
    try:
        executor.spin_until_future_complete(future, timeout_sec=timeout_sec)
    finally:
        executor.remove_node(node)


_not_provided = not_provided_attributes("rclpy", ("lifecycle", "wait_for_message", "type_support", "experimental"))


def __getattr__(name: str) -> Any:
    if name == "action":  # a subpackage: imported on first use, as `import rclpy.action` does
        import importlib

        return importlib.import_module("services.ros.rclpy.action")
    return _not_provided(name)
