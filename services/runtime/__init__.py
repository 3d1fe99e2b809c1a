"""The Skydeck node SDK: rclpy's shape, asyncio underneath.

    from services.runtime import Node, spin

    class SendMessageNode(Node):
        def __init__(self):
            super().__init__("send_message_node")
            self.publisher = self.create_publisher(PointStamped, "/my_point", 10)
            self.create_timer(0.1, self.run_loop)

    spin(SendMessageNode())
"""

from services.runtime.client import Client
from services.runtime.clock import Clock, ClockTime
from services.runtime.errors import (
    NodeError,
    ServiceCallRejectedError,
    ServiceError,
    ServiceException,
    ServiceTimeoutError,
    ServiceUnavailableError,
    SkydeckError,
)
from services.runtime.logger import NodeLogger
from services.runtime.node import Node
from services.runtime.publisher import Publisher
from services.runtime.service import Service
from services.runtime.settings import NodeSettings
from services.runtime.spin import init, shutdown, spin
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
