"""The Skydeck node SDK: rclpy's shape, asyncio underneath.

    from services.runtime import Node, spin

    class SendMessageNode(Node):
        def __init__(self):
            super().__init__("send_message_node")
            self.publisher = self.create_publisher(PointStamped, "/my_point", 10)
            self.create_timer(0.1, self.run_loop)

    spin(SendMessageNode())

The exports load lazily, so a process that needs only a light part (the launch supervisor's HTTP
client, the CLI's settings) does not pay for FastAPI and uvicorn.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from shared_models.lazy import lazy_exports

if TYPE_CHECKING:
    from services.runtime.client import Client
    from services.runtime.clock import (
        Clock,
        ClockTime,
    )
    from services.runtime.errors import (
        NodeError,
        ServiceCallRejectedError,
        ServiceError,
        ServiceException,
        ServiceTimeoutError,
        ServiceUnavailableError,
        SkydeckError,
    )
    from services.runtime.executor import (
        init,
        shutdown,
        spin,
    )
    from services.runtime.logger import NodeLogger
    from services.runtime.node import Node
    from services.runtime.parameter import Parameter
    from services.runtime.parameters import ParameterException
    from services.runtime.publisher import Publisher
    from services.runtime.service import Service
    from services.runtime.settings import NodeSettings
    from services.runtime.subscription import Subscription
    from services.runtime.timer import Timer

__all__ = [
    "Client",
    "Clock",
    "ClockTime",
    "Node",
    "NodeError",
    "NodeLogger",
    "NodeSettings",
    "Parameter",
    "ParameterException",
    "Publisher",
    "Service",
    "ServiceCallRejectedError",
    "ServiceError",
    "ServiceException",
    "ServiceTimeoutError",
    "ServiceUnavailableError",
    "SkydeckError",
    "Subscription",
    "Timer",
    "init",
    "shutdown",
    "spin",
]

_HOMES = {
    "Client": "services.runtime.client",
    "Clock": "services.runtime.clock",
    "ClockTime": "services.runtime.clock",
    "Node": "services.runtime.node",
    "NodeError": "services.runtime.errors",
    "NodeLogger": "services.runtime.logger",
    "NodeSettings": "services.runtime.settings",
    "Parameter": "services.runtime.parameter",
    "ParameterException": "services.runtime.parameters",
    "Publisher": "services.runtime.publisher",
    "Service": "services.runtime.service",
    "ServiceCallRejectedError": "services.runtime.errors",
    "ServiceError": "services.runtime.errors",
    "ServiceException": "services.runtime.errors",
    "ServiceTimeoutError": "services.runtime.errors",
    "ServiceUnavailableError": "services.runtime.errors",
    "SkydeckError": "services.runtime.errors",
    "Subscription": "services.runtime.subscription",
    "Timer": "services.runtime.timer",
    "init": "services.runtime.executor",
    "shutdown": "services.runtime.executor",
    "spin": "services.runtime.executor",
}


__getattr__ = lazy_exports(__name__, _HOMES)
