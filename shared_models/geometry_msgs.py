"""geometry_msgs: points, vectors, orientations, poses, transforms, polygons, twists, accelerations
and wrenches, with their stamped and covariance forms."""

from __future__ import annotations

from pydantic import Field

from shared_models._message import Float32, Float64, Message, String, fixed_floats
from shared_models.std_msgs import Header

__all__ = [
    "Accel",
    "AccelStamped",
    "Point",
    "Point32",
    "PointStamped",
    "Polygon",
    "PolygonStamped",
    "Pose",
    "Pose2D",
    "PoseArray",
    "PoseStamped",
    "PoseWithCovariance",
    "PoseWithCovarianceStamped",
    "Quaternion",
    "QuaternionStamped",
    "Transform",
    "TransformStamped",
    "Twist",
    "TwistStamped",
    "TwistWithCovariance",
    "TwistWithCovarianceStamped",
    "Vector3",
    "Vector3Stamped",
    "Wrench",
    "WrenchStamped",
]

# The row-major 6x6 covariance of (x, y, z, rotation about X, about Y, about Z).
_COVARIANCE_COMMENT = (
    "# Row-major representation of the 6x6 covariance matrix\n"
    "# The orientation parameters use a fixed-axis representation.\n"
    "# In order, the parameters are:\n"
    "# (x, y, z, rotation about X axis, rotation about Y axis, rotation about Z axis)"
)


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


class Vector3Stamped(Message):
    """A vector with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/Vector3Stamped"
    __ros_comment__ = "# This represents a Vector3 with reference coordinate frame and timestamp"

    header: Header = Field(default_factory=Header)
    vector: Vector3 = Field(default_factory=Vector3)


class QuaternionStamped(Message):
    """An orientation with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/QuaternionStamped"
    __ros_comment__ = (
        "# This represents an orientation with reference coordinate frame and timestamp."
    )

    header: Header = Field(default_factory=Header)
    quaternion: Quaternion = Field(default_factory=Quaternion)


class PolygonStamped(Message):
    """A polygon with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/PolygonStamped"
    __ros_comment__ = "# This represents a Polygon with reference coordinate frame and timestamp"

    header: Header = Field(default_factory=Header)
    polygon: Polygon = Field(default_factory=Polygon)


class Pose2D(Message):
    """A position and heading in the plane (deprecated in ROS 2, still common)."""

    __ros_type__ = "geometry_msgs/msg/Pose2D"
    __ros_comment__ = (
        "# Deprecated as of Foxy and will potentially be removed in any following release.\n"
        "# Please use the full 3D pose.\n"
        "# This expresses a position and orientation on a 2D manifold."
    )

    x: Float64 = 0.0
    y: Float64 = 0.0
    theta: Float64 = 0.0


class PoseWithCovariance(Message):
    """A pose with its uncertainty: a row-major 6x6 covariance (36 numbers)."""

    __ros_type__ = "geometry_msgs/msg/PoseWithCovariance"
    __ros_comment__ = (
        "# This represents a pose in free space with uncertainty.\n" + _COVARIANCE_COMMENT
    )

    pose: Pose = Field(default_factory=Pose)
    covariance: list[Float64] = fixed_floats(36)


class PoseWithCovarianceStamped(Message):
    """A pose with uncertainty, a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/PoseWithCovarianceStamped"
    __ros_comment__ = (
        "# This expresses an estimated pose with a reference coordinate frame and timestamp"
    )

    header: Header = Field(default_factory=Header)
    pose: PoseWithCovariance = Field(default_factory=PoseWithCovariance)


class TwistWithCovariance(Message):
    """A twist with its uncertainty: a row-major 6x6 covariance (36 numbers)."""

    __ros_type__ = "geometry_msgs/msg/TwistWithCovariance"
    __ros_comment__ = (
        "# This expresses velocity in free space with uncertainty.\n" + _COVARIANCE_COMMENT
    )

    twist: Twist = Field(default_factory=Twist)
    covariance: list[Float64] = fixed_floats(36)


class TwistWithCovarianceStamped(Message):
    """A twist with uncertainty, a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/TwistWithCovarianceStamped"
    __ros_comment__ = (
        "# This represents an estimated twist with reference coordinate frame and timestamp."
    )

    header: Header = Field(default_factory=Header)
    twist: TwistWithCovariance = Field(default_factory=TwistWithCovariance)


class Accel(Message):
    """Acceleration: linear (m/s^2) and angular (rad/s^2) parts."""

    __ros_type__ = "geometry_msgs/msg/Accel"
    __ros_comment__ = (
        "# This expresses acceleration in free space broken into its linear and angular parts."
    )

    linear: Vector3 = Field(default_factory=Vector3)
    angular: Vector3 = Field(default_factory=Vector3)


class AccelStamped(Message):
    """An acceleration with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/AccelStamped"
    __ros_comment__ = "# An accel with reference coordinate frame and timestamp"

    header: Header = Field(default_factory=Header)
    accel: Accel = Field(default_factory=Accel)


class Wrench(Message):
    """Force (N) and torque (N m)."""

    __ros_type__ = "geometry_msgs/msg/Wrench"
    __ros_comment__ = (
        "# This represents force in free space, separated into its linear and angular parts."
    )

    force: Vector3 = Field(default_factory=Vector3)
    torque: Vector3 = Field(default_factory=Vector3)


class WrenchStamped(Message):
    """A wrench with a frame and a timestamp."""

    __ros_type__ = "geometry_msgs/msg/WrenchStamped"
    __ros_comment__ = "# A wrench with reference coordinate frame and timestamp"

    header: Header = Field(default_factory=Header)
    wrench: Wrench = Field(default_factory=Wrench)


class Transform(Message):
    """How to move from one frame into another: a translation, then a rotation."""

    __ros_type__ = "geometry_msgs/msg/Transform"
    __ros_comment__ = (
        "# This represents the transform between two coordinate frames in free space."
    )

    translation: Vector3 = Field(default_factory=Vector3)
    rotation: Quaternion = Field(default_factory=Quaternion)


class TransformStamped(Message):
    """The transform from ``header.frame_id`` to ``child_frame_id`` at ``header.stamp`` (a TF edge).

    Example::

        TransformStamped(
            header=Header(frame_id="odom"),
            child_frame_id="base_link",
            transform=Transform(translation=Vector3(x=1.0)),
        )
    """

    __ros_type__ = "geometry_msgs/msg/TransformStamped"
    __ros_comment__ = (
        "# This expresses a transform from coordinate frame header.frame_id\n"
        "# to the coordinate frame child_frame_id at the time of header.stamp\n"
        "#\n"
        "# This message is mostly used by the\n"
        "# <a href=\"https://docs.ros.org/en/rolling/p/tf2/\">tf2</a> package."
    )

    header: Header = Field(default_factory=Header)
    child_frame_id: String = ""  # the frame id of the child frame
    transform: Transform = Field(default_factory=Transform)
