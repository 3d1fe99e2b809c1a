"""Perception turns the simulator's PoseArray into a Polygon of box positions."""

from __future__ import annotations

from services.perception.node import boxes_to_polygon
from shared_models.geometry_msgs import Point, Pose, PoseArray, Quaternion


def test_positions_kept_in_order_orientation_dropped() -> None:
    boxes = PoseArray(
        poses=[
            Pose(position=Point(x=1.0, y=2.0, z=1.0), orientation=Quaternion(x=0.1, y=0.2, z=0.3, w=0.9)),
            Pose(position=Point(x=-5.0, y=7.5, z=1.0)),
        ]
    )
    polygon = boxes_to_polygon(boxes)
    assert [(p.x, p.y, p.z) for p in polygon.points] == [(1.0, 2.0, 1.0), (-5.0, 7.5, 1.0)]


def test_no_boxes_no_points() -> None:
    assert boxes_to_polygon(PoseArray()).points == []
