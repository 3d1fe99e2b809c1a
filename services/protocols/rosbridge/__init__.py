"""rosbridge v2 for roslibjs and roslibpy clients, with rosapi: the core's ``rosbridge`` endpoint.

``PLUGIN`` is what the table of endpoints (:mod:`services.protocols.endpoints`) names: started
with the core, it hosts rosapi and tf2_web_republisher and serves connections on the endpoint's own port (9090) and at
``/rosbridge`` on the core's port. See docs/protocols.md.
"""

from __future__ import annotations

from services.core.access import CoreAccess
from services.core.endpoint_servers import EndpointPlugin
from services.protocols.rosbridge.endpoint import RosbridgeEndpoint
from services.protocols.rosbridge.rosapi import host_rosapi
from services.protocols.rosbridge.tf_republisher import TFRepublisher

__all__ = ["PLUGIN", "RosbridgeEndpoint"]


def _start(access: CoreAccess) -> RosbridgeEndpoint:
    host_rosapi(access)
    return RosbridgeEndpoint(access, TFRepublisher(access))


PLUGIN = EndpointPlugin(
    name="rosbridge",
    start=_start,
    greeting=(
        "Skydeck's rosbridge v2 endpoint: connect roslibjs or roslibpy here with a WebSocket "
        "(new ROSLIB.Ros({url: 'ws://HOST:PORT'})). See docs/protocols.md.\n"
    ),
    core_path="/rosbridge",
)
