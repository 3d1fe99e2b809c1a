"""``skydeck bridge ros2``: Skydeck on a ROS 2 DDS domain, topics and services both ways."""

from __future__ import annotations

import argparse

__all__ = ["add_parser"]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    bridge = subparsers.add_parser("bridge", help="join another robotics system (ROS 2 over DDS)")
    kinds = bridge.add_subparsers(dest="kind", required=True, metavar="SYSTEM")
    p = kinds.add_parser("ros2", help="bridge topics and services both ways with ROS 2 nodes on a DDS domain")
    p.add_argument("--domain", type=int, default=None, help="the DDS domain id (default: ROS_DOMAIN_ID, else 0)")
    p.add_argument("--topics", default=".*", metavar="REGEX", help="bridge only topics whose name matches (default: all)")
    p.add_argument("--services", default=".*", metavar="REGEX", help="bridge only services whose name matches (default: all)")
    p.set_defaults(func=_ros2)


def _ros2(args: argparse.Namespace) -> int:
    from services.protocols.ros2.main import run_bridge

    return run_bridge(args.domain, args.topics, args.services)
