"""Whether the bridge's dependencies (the ``ros2`` extra) are here, said in one line each.

Checked without importing rclpy (which is heavy, and inside ``skydeck run`` is Skydeck's own
façade): from the installed distributions and the interface build's digest.
"""

from __future__ import annotations

import re
from importlib.metadata import PackageNotFoundError, version
from typing import Any

from services.protocols.ros2.interface_build import packages_to_build, stamp_path

__all__ = ["INSTALL_HINT", "doctor_findings", "missing_extra", "missing_interfaces"]

INSTALL_HINT = "run `make install-ros2` (or `pip install -e '.[ros2]'`, then `python -m services.protocols.ros2.interface_build`)"
# The distributions without which there is no DDS side at all.
_NEEDED = ("ros-rclpy", "ros-rmw-fastrtps-cpp", "ros-std-msgs")


def missing_extra() -> str | None:
    """Why the bridge cannot run here (one line), or None when the extra is installed."""
    missing = []
    for distribution in _NEEDED:
        try:
            version(distribution)
        except PackageNotFoundError:
            missing.append(distribution)
    if missing:
        return f"the ROS 2 bridge needs ROS 2's Python packages ({', '.join(missing)} not installed): {INSTALL_HINT}"
    return None


def missing_interfaces() -> list[str]:
    """Skydeck's message packages that have no ROS 2 interface package built yet."""
    from services.protocols.ros2.interface_build import _digest

    packages = packages_to_build()
    stamp = stamp_path()
    if stamp.exists() and stamp.read_text().strip() == _digest(packages):
        return []
    return packages


def doctor_findings(graph: dict[str, Any] | None) -> list[tuple[str, str, str]]:
    """``skydeck doctor``'s lines about the bridge: (status, what, fix). ``graph`` is the core's
    ``/api/graph`` (None without a core): a running bridge says which domain it joined."""
    findings = []
    if missing_extra() is not None:
        findings.append(("warn", "ROS 2 bridge: its extra is not installed (optional)", INSTALL_HINT))
    else:
        findings.append(("ok", f"ROS 2 bridge: rclpy {version('ros-rclpy')} over Fast DDS {version('ros-fastdds')}", ""))
        missing = missing_interfaces()
        if missing:
            findings.append(("warn", f"ROS 2 bridge: interfaces not built for {', '.join(missing)}", INSTALL_HINT))
    for node in (graph or {}).get("nodes", []):
        match = _BRIDGE.fullmatch(node["name"])
        if match is not None:
            ros2_nodes = sum(1 for n in (graph or {})["nodes"] if n.get("via") == node["name"])
            findings.append(("ok", f"ROS 2 bridge {node['name']} joined DDS domain {match['domain'] or 0} ({ros2_nodes} ROS 2 node(s) seen)", ""))
    return findings


# The bridge's node name says its domain (bridge.bridge_node_name).
_BRIDGE = re.compile(r"/ros2_bridge(?:_(?P<domain>\d+))?")
