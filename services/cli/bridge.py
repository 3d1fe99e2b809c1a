"""``skydeck bridge ros2``: Skydeck on a ROS 2 DDS domain, topics and services both ways."""

from __future__ import annotations

import argparse

from services.protocols.ros2.main import add_bridge_arguments

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    bridge = subparsers.add_parser("bridge", help="join another robotics system (ROS 2 over DDS)")
    kinds = bridge.add_subparsers(dest="kind", required=True, metavar="SYSTEM")
    p = kinds.add_parser("ros2", help="bridge topics and services both ways with ROS 2 nodes on a DDS domain")
    add_bridge_arguments(p)
    p.set_defaults(func=_ros2)


def _ros2(args: argparse.Namespace) -> int:
    from services.protocols.ros2.main import run_bridge

    return run_bridge(args.domain, args.topics, args.services)
