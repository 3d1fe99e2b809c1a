"""Which kind of service a name is, so that ``skydeck service list`` and the core's ``/docs``
lead with the world's own commands (``/control/take_off``), then the nodes' parameter services,
then Skydeck's own machinery (rosapi, the launch's node).

    service_group("/control/take_off", "/control")      # ServiceGroup.COMMAND
    service_group("/control/get_parameters", "/control") # ServiceGroup.PARAMETERS
    service_group("/rosapi/topics", "/rosapi")           # ServiceGroup.SYSTEM
"""

from __future__ import annotations

import enum

from services.runtime.parameter_service import is_parameter_service

__all__ = ["SYSTEM_NODES", "ServiceGroup", "service_group"]

SYSTEM_NODES = frozenset({"/skydeck_core", "/skydeck_launch", "/rosapi", "/tf2_web_republisher"})
"""Skydeck's own nodes: the core, the launch's node (``skydeck node kill`` asks it), and rosapi and
tf2_web_republisher, which the core answers for rosbridge clients (ROS's nodes of those names). Named here, not imported from
the core and the launch, which are layers above the runtime; a test pins them to theirs."""


class ServiceGroup(enum.IntEnum):
    """A service's kind, in the order lists show them."""

    COMMAND = 0
    """What the world's nodes do: take off, fly, reset the simulator, a user's own services."""
    PARAMETERS = 1
    """A node's six parameter services (ROS 2's ``/NODE/get_parameters``, ...)."""
    SYSTEM = 2
    """Served by Skydeck's own nodes, for its tools and protocol clients."""


def service_group(service: str, node: str) -> ServiceGroup:
    """The kind of service ``service``, served by node ``node``."""
    if node in SYSTEM_NODES:
        return ServiceGroup.SYSTEM
    if is_parameter_service(node, service):
        return ServiceGroup.PARAMETERS
    return ServiceGroup.COMMAND
