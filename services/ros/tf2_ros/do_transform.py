"""A TransformStamped applied to the stamped geometry_msgs types (``tf2_geometry_msgs``):

    point_in_odom = do_transform_point(point_in_base_link, buffer.lookup_transform('odom', 'base_link', Time()))

Each result carries the transform's header (its target frame and stamp), as tf2_geometry_msgs
sets it. ``do_transform_pose`` takes a Pose (ROS 2, returns a Pose) or a PoseStamped (ROS 1,
returns a PoseStamped). Every function is registered for ``Buffer.transform``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from services.ros.tf2_ros.buffer_interface import TransformRegistration
from services.ros.tf2_ros.rigid import Rigid, quaternion_multiply, rotate
from services.ros.tf_transformations.quaternions import quaternion_matrix
from shared_models.geometry_msgs import (
    Point,
    Point32,
    PointStamped,
    Polygon,
    PolygonStamped,
    Pose,
    PoseStamped,
    PoseWithCovariance,
    PoseWithCovarianceStamped,
    Quaternion,
    QuaternionStamped,
    TransformStamped,
    Vector3,
    Vector3Stamped,
)

__all__ = [
    "do_transform_point",
    "do_transform_polygon_stamped",
    "do_transform_pose",
    "do_transform_pose_stamped",
    "do_transform_pose_with_covariance_stamped",
    "do_transform_quaternion",
    "do_transform_vector3",
    "transform_covariance",
]


def _rigid(transform: TransformStamped) -> Rigid:
    if not isinstance(transform, TransformStamped):
        raise TypeError(f"the transform must be a geometry_msgs TransformStamped, got {type(transform).__name__}")
    return Rigid.from_msg(transform.transform)


def _header(transform: TransformStamped) -> Any:
    return transform.header.model_copy(deep=True)


def do_transform_point(point: PointStamped, transform: TransformStamped) -> PointStamped:
    """``point`` in the transform's target frame."""
    x, y, z = _rigid(transform).apply((point.point.x, point.point.y, point.point.z))
    return PointStamped(header=_header(transform), point=Point(x=x, y=y, z=z))


def do_transform_vector3(vector3: Vector3Stamped, transform: TransformStamped) -> Vector3Stamped:
    """``vector3`` rotated into the target frame (a direction: the translation does not apply)."""
    x, y, z = rotate(_rigid(transform).rotation, (vector3.vector.x, vector3.vector.y, vector3.vector.z))
    return Vector3Stamped(header=_header(transform), vector=Vector3(x=x, y=y, z=z))


def _pose(pose: Pose, rigid: Rigid) -> Pose:
    p, o = pose.position, pose.orientation
    x, y, z = rigid.apply((p.x, p.y, p.z))
    qx, qy, qz, qw = quaternion_multiply(rigid.rotation, (o.x, o.y, o.z, o.w))
    return Pose(position=Point(x=x, y=y, z=z), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw))


def do_transform_pose(pose: Pose | PoseStamped, transform: TransformStamped) -> Pose | PoseStamped:
    """A Pose (ROS 2) or a PoseStamped (ROS 1) in the target frame."""
    if isinstance(pose, PoseStamped):
        return do_transform_pose_stamped(pose, transform)
    if not isinstance(pose, Pose):
        raise TypeError(f"do_transform_pose takes a Pose or a PoseStamped, got {type(pose).__name__}")
    return _pose(pose, _rigid(transform))


def do_transform_pose_stamped(pose: PoseStamped, transform: TransformStamped) -> PoseStamped:
    """A PoseStamped in the target frame."""
    return PoseStamped(header=_header(transform), pose=_pose(pose.pose, _rigid(transform)))


def do_transform_quaternion(quaternion: QuaternionStamped, transform: TransformStamped) -> QuaternionStamped:
    """An orientation in the target frame."""
    q = quaternion.quaternion
    x, y, z, w = quaternion_multiply(_rigid(transform).rotation, (q.x, q.y, q.z, q.w))
    return QuaternionStamped(header=_header(transform), quaternion=Quaternion(x=x, y=y, z=z, w=w))


def transform_covariance(covariance: Any, transform: TransformStamped) -> list[float]:
    """A row-major 6x6 pose covariance seen from the target frame: ``J C J^T`` with ``J`` the
    rotation twice on the diagonal (the position and the rotation axes both turn with the frame)."""
    matrix = np.asarray(covariance, dtype=np.float64)
    if matrix.shape != (36,):
        raise ValueError(f"a pose covariance has 36 numbers (6x6, row-major), got {matrix.size}")
    rotation = quaternion_matrix(_rigid(transform).rotation)[:3, :3]
    turn = np.zeros((6, 6))
    turn[:3, :3] = turn[3:, 3:] = rotation
    return [float(v) for v in (turn @ matrix.reshape(6, 6) @ turn.T).ravel()]


def do_transform_pose_with_covariance_stamped(
    pose: PoseWithCovarianceStamped, transform: TransformStamped
) -> PoseWithCovarianceStamped:
    """A pose with its covariance in the target frame."""
    return PoseWithCovarianceStamped(
        header=_header(transform),
        pose=PoseWithCovariance(
            pose=_pose(pose.pose.pose, _rigid(transform)),
            covariance=transform_covariance(list(pose.pose.covariance), transform),
        ),
    )


def do_transform_polygon_stamped(polygon: PolygonStamped, transform: TransformStamped) -> PolygonStamped:
    """Each corner of a polygon in the target frame."""
    rigid = _rigid(transform)
    points = []
    for corner in polygon.polygon.points:
        x, y, z = rigid.apply((corner.x, corner.y, corner.z))
        points.append(Point32(x=x, y=y, z=z))
    return PolygonStamped(header=_header(transform), polygon=Polygon(points=points))


_registry = TransformRegistration()
_registry.add(PointStamped, do_transform_point)
_registry.add(Vector3Stamped, do_transform_vector3)
_registry.add(PoseStamped, do_transform_pose_stamped)
_registry.add(QuaternionStamped, do_transform_quaternion)
_registry.add(PoseWithCovarianceStamped, do_transform_pose_with_covariance_stamped)
_registry.add(PolygonStamped, do_transform_polygon_stamped)
