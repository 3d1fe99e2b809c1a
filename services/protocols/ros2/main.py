"""The bridge's entries: ``skydeck bridge ros2`` and ``skydeck run ros2_bridge`` (launch's
``--ros2``): check the options and the extra, then run the bridge node until stopped."""

from __future__ import annotations

import argparse
import re

from shared_models.errors import SkydeckError

__all__ = ["BridgeUnavailable", "add_bridge_arguments", "main", "run_bridge"]

class BridgeUnavailable(SkydeckError):
    """The bridge cannot start here: its extra is missing, or an option is wrong."""


def add_bridge_arguments(parser: argparse.ArgumentParser) -> None:
    """The bridge's options, the same for both entries."""
    parser.add_argument("--domain", type=int, default=None, help="the DDS domain id (default: ROS_DOMAIN_ID, else 0)")
    parser.add_argument("--topics", default=".*", metavar="REGEX", help="bridge only topics whose name matches (default: all)")
    parser.add_argument("--services", default=".*", metavar="REGEX", help="bridge only services whose name matches (default: all)")


def main(argv: list[str] | None = None) -> int:
    """``skydeck run ros2_bridge [--domain N] [--topics RE] [--services RE]``."""
    parser = argparse.ArgumentParser(prog="skydeck run ros2_bridge", description="the ROS 2 bridge (see `skydeck bridge ros2`)")
    add_bridge_arguments(parser)
    args = parser.parse_args(argv)
    return run_bridge(args.domain, args.topics, args.services)


def run_bridge(domain: int | None, topics: str, services: str) -> int:
    """Run the bridge on ``domain`` (default: ROS_DOMAIN_ID, else 0) until Ctrl-C or SIGTERM."""
    # Imported here: the CLI loads this module for its options on every command.
    from pydantic import ValidationError

    from services.protocols.ros2.extra import missing_extra, missing_interfaces
    from services.protocols.ros2.settings import MAX_DOMAIN, Ros2Settings

    try:
        ros2 = Ros2Settings()
    except ValidationError as error:
        raise BridgeUnavailable(f"ROS_DOMAIN_ID: {error.errors()[0]['msg']} (a DDS domain id, 0 to {MAX_DOMAIN})") from None
    domain = ros2.domain_id if domain is None else domain
    if not 0 <= domain <= MAX_DOMAIN:
        raise BridgeUnavailable(f"--domain must be 0 to {MAX_DOMAIN}, not {domain}")
    for flag, pattern in (("--topics", topics), ("--services", services)):
        try:
            re.compile(pattern)
        except re.error as error:
            raise BridgeUnavailable(f"{flag} {pattern!r} is not a regular expression: {error}") from None
    reason = missing_extra()
    if reason is not None:
        raise BridgeUnavailable(reason)
    import logging

    from services.protocols.ros2.bridge import Ros2Bridge
    from services.runtime import spin

    missing = missing_interfaces()
    if missing:
        logging.getLogger("skydeck.ros2").warning(
            "skydeck: the ROS 2 interfaces of %s are not built, so their topics are not bridged: "
            "run `make install-ros2`", ", ".join(missing),
        )
    spin(Ros2Bridge(domain, topics, services, discovery=ros2.discovery()))
    return 0
