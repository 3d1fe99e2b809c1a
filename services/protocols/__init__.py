"""Protocol adapters over the core: rosbridge v2 and the Foxglove WebSocket protocol; and, in a
process of its own rather than plugged into the core, the ROS 2 bridge (``ros2/``: DDS).

Each protocol is a package of its own (``rosbridge/``, ``foxglove/``) that translates its frames
to the core's one topic edge and one service-call path and owns nothing else; it declares an
:class:`~services.core.endpoint_servers.EndpointPlugin` as ``PLUGIN``. What they share is here:
the table of endpoints (:mod:`.endpoints`: name, default port, flag, environment variable),
the ``skydeck core`` process that plugs them into the core (:mod:`.core_process`, the one
registration point), a connection's session with the core (:mod:`.session`), the reading and
refusing of JSON ops (:mod:`.ops`) and node parameters (:mod:`.parameters`).

The core never imports this package; importing it loads only the table (the protocols load
when the process that serves them starts). See docs/protocols.md.
"""

from services.protocols.endpoints import ENDPOINTS, Endpoint

__all__ = ["ENDPOINTS", "ROS_DISTRO", "Endpoint"]

ROS_DISTRO = "humble"
"""The ROS 2 distribution whose definitions Skydeck follows (rosapi's and Foxglove's server
metadata say it; see docs/architecture.md)."""
