"""Perception (the workshop's first coding task): ``/simulator/boxes`` PoseArray in,
``/perception/boxes`` Polygon out, the boxes' positions with their orientation dropped."""

from __future__ import annotations

import argparse

from services.runtime import Node, NodeSettings, spin
from services.runtime.settings import node_settings
from shared_models.geometry_msgs import Point32, Polygon, PoseArray

__all__ = ["PerceptionNode", "boxes_to_polygon", "main"]

DEFAULT_PORT = 8002


def boxes_to_polygon(boxes: PoseArray) -> Polygon:
    """The positions of the boxes as a Polygon, in the same order (indices are box ids)."""
    return Polygon(points=[Point32(x=p.position.x, y=p.position.y, z=p.position.z) for p in boxes.poses])


class PerceptionNode(Node):
    """Republishes every box message as a Polygon, as soon as it arrives."""

    def __init__(self, settings: NodeSettings | None = None) -> None:
        super().__init__("perception", settings=settings or node_settings().with_default_port(DEFAULT_PORT))
        self.publisher = self.create_publisher(Polygon, "/perception/boxes", 1, latched=True)
        self.create_subscription(PoseArray, "/simulator/boxes", self.callback, 1)

    def callback(self, message: PoseArray) -> None:
        self.publisher.publish(boxes_to_polygon(message))


def main(argv: list[str] | None = None) -> int:
    """``skydeck run perception``."""
    argparse.ArgumentParser(prog="skydeck run perception", description=__doc__).parse_args(argv)
    spin(PerceptionNode())
    return 0
