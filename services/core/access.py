"""What a protocol endpoint may use of the core: one object handed to every endpoint plugin.

Topics go through the core node (:class:`~services.core.gateway_topic.GatewayTopic`), service
calls through the one call path (:class:`~services.core.service_calls.ServiceCalls`), each
connection is a guest in the graph (:class:`~services.core.guests.Guests`), admitted by the
core's fences (:class:`~services.access.Fences`: what its token may do), and ROS 1's
parameters are the core's parameter server (rosapi's ``get_param`` of a ROS 1 name). The registry is
read, never written, by endpoints. The core builds it when it starts and gives it to each
plugin (:mod:`services.core.endpoint_servers`); it knows nothing of the protocols themselves.
"""

from __future__ import annotations

from dataclasses import dataclass

from services.access import Fences
from services.core.core_node import CoreNode
from services.core.gateway import Gateway
from services.core.guests import Guests
from services.core.parameter_server import ParameterTree
from services.core.registry import Registry
from services.core.service_calls import ServiceCalls
from services.core.settings import CoreSettings

__all__ = ["CoreAccess"]


@dataclass(frozen=True)
class CoreAccess:
    """The core's parts a protocol endpoint uses (see the module docstring)."""

    core: CoreNode
    registry: Registry
    guests: Guests
    calls: ServiceCalls
    gateway: Gateway
    settings: CoreSettings
    fences: Fences
    rosparam: ParameterTree
