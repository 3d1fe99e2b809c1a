"""geometry_msgs: points, vectors, orientations, poses, polygons and twists."""

from __future__ import annotations

from pydantic import Field

from shared_models._message import Float32, Float64, Message
from shared_models.std_msgs import Header

__all__ = [
    "Point",
    "Point32",
    "PointStamped",
    "Polygon",
    "Pose",
    "PoseArray",
    "PoseStamped",
    "Quaternion",
    "Twist",
    "TwistStamped",
    "Vector3",
]


class Point(Message):
    """A position in free space (metres)."""

    __ros_type__ = "geometry_msgs/msg/Point"
    __ros_comment__ = "# This contains the position of a point in free space"

    x: Float64 = 0.0
    y: Float64 = 0.0
    z: Float64 = 0.0


class Point32(Message):
    """A position in free space with 32 bits of precision."""

    __ros_type__ = "geometry_msgs/msg/Point32"
    __ros_comment__ = (
        "# This contains the position of a point in free space(with 32 bits of precision).\n"
        "# It is recommended to use Point wherever possible instead of Point32."
    )

    x: Float32 = 0.0
    y: Float32 = 0.0
    z: Float32 = 0.0


class Vector3(Message):
    """A vector in free space, anchored at the origin."""

    __ros_type__ = "geometry_msgs/msg/Vector3"
    __ros_comment__ = (
        "# This represents a vector in free space.\n"
        "# This is semantically different than a point.\n"
        "# A vector is always anchored at the origin.\n"
        "# When a transform is applied to a vector, only the rotational component is applied."
    )

    x: Float64 = 0.0
    y: Float64 = 0.0
    z: Float64 = 0.0


class Quaternion(Message):
    """An orientation as a quaternion; the default is the identity (w=1)."""

    __ros_type__ = "geometry_msgs/msg/Quaternion"
    __ros_comment__ = "# This represents an orientation in free space in quaternion form."

    x: Float64 = 0.0
    y: Float64 = 0.0
    z: Float64 = 0.0
    w: Float64 = 1.0


class Pose(Message):
    """A position and an orientation."""

    __ros_type__ = "geometry_msgs/msg/Pose"
    __ros_comment__ = (
        "# A representation of pose in free space, composed of position and orientation."
    )

    position: Point = Field(default_factory=Point)
    orientation: Quaternion = Field(default_factory=Quaternion)


class PoseStamped(Message):
    """A pose with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/PoseStamped"
    __ros_comment__ = "# A Pose with reference coordinate frame and timestamp"

    header: Header = Field(default_factory=Header)
    pose: Pose = Field(default_factory=Pose)


class PoseArray(Message):
    """Several poses in one frame."""

    __ros_type__ = "geometry_msgs/msg/PoseArray"
    __ros_comment__ = "# An array of poses with a header for global reference."

    header: Header = Field(default_factory=Header)
    poses: list[Pose] = Field(default_factory=list)


class Polygon(Message):
    """A polygon; the first and last points are connected."""

    __ros_type__ = "geometry_msgs/msg/Polygon"
    __ros_comment__ = (
        "# A specification of a polygon where the first and last points are assumed to be connected"
    )

    points: list[Point32] = Field(default_factory=list)


class PointStamped(Message):
    """A point with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/PointStamped"
    __ros_comment__ = "# This represents a Point with reference coordinate frame and timestamp"

    header: Header = Field(default_factory=Header)
    point: Point = Field(default_factory=Point)


class Twist(Message):
    """Velocity: linear (m/s) and angular (rad/s) parts."""

    __ros_type__ = "geometry_msgs/msg/Twist"
    __ros_comment__ = (
        "# This expresses velocity in free space broken into its linear and angular parts."
    )

    linear: Vector3 = Field(default_factory=Vector3)
    angular: Vector3 = Field(default_factory=Vector3)


class TwistStamped(Message):
    """A twist with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/TwistStamped"
    __ros_comment__ = "# A twist with reference coordinate frame and timestamp"

    header: Header = Field(default_factory=Header)
    twist: Twist = Field(default_factory=Twist)
