"""``skydeck bridge ros2``'s entry: check the extra, then run the bridge node until stopped."""

from __future__ import annotations

import re

from services.protocols.ros2.extra import default_domain, missing_extra, missing_interfaces
from shared_models.errors import SkydeckError

__all__ = ["BridgeUnavailable", "run_bridge"]

_MAX_DOMAIN = 232  # ROS 2's highest domain id (its UDP ports run out above it)


class BridgeUnavailable(SkydeckError):
    """The bridge cannot start here: its extra is missing, or an option is wrong."""


def run_bridge(domain: int | None, topics: str, services: str) -> int:
    """Run the bridge on ``domain`` (default: ROS_DOMAIN_ID, else 0) until Ctrl-C or SIGTERM."""
    domain = default_domain() if domain is None else domain
    if not 0 <= domain <= _MAX_DOMAIN:
        raise BridgeUnavailable(f"--domain must be 0 to {_MAX_DOMAIN}, not {domain}")
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
    spin(Ros2Bridge(domain, topics, services))
    return 0
