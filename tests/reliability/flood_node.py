"""A node for the flood test, run as its own process (`skydeck run tests/reliability/flood_node.py`):
echoes every String it receives on /flood/in to /flood/out."""

from __future__ import annotations

from services.runtime import Node, spin
from shared_models.std_msgs import String


class FloodNode(Node):
    def __init__(self) -> None:
        super().__init__("flood")
        self.out = self.create_publisher(String, "/flood/out", 100)
        self.create_subscription(String, "/flood/in", self.out.publish, 100)


if __name__ == "__main__":
    spin(FloodNode())
