"""nav_msgs: odometry, paths and occupancy-grid maps."""

from __future__ import annotations

from pydantic import Field

from shared_models._message import Float32, Int8, Message, String, UInt32
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import (
    Pose,
    PoseStamped,
    PoseWithCovariance,
    TwistWithCovariance,
)
from shared_models.std_msgs import Header

__all__ = ["MapMetaData", "OccupancyGrid", "Odometry", "Path"]


class Odometry(Message):
    """Where a robot thinks it is and how fast it moves: ``pose`` in ``header.frame_id`` (``odom``),
    ``twist`` in ``child_frame_id`` (``base_link``).

    Example::

        odom.pose.pose.position.x, odom.twist.twist.angular.z
    """

    __ros_type__ = "nav_msgs/msg/Odometry"
    __ros_comment__ = (
        "# This represents an estimate of a position and velocity in free space.\n"
        "# The pose in this message should be specified in the coordinate frame given by\n"
        "# header.frame_id, the twist in the coordinate frame given by the child_frame_id"
    )

    header: Header = Field(default_factory=Header)
    child_frame_id: String = ""  # the frame the pose points to, and the twist's frame
    pose: PoseWithCovariance = Field(default_factory=PoseWithCovariance)
    twist: TwistWithCovariance = Field(default_factory=TwistWithCovariance)


class Path(Message):
    """A path for a robot to follow: poses in order."""

    __ros_type__ = "nav_msgs/msg/Path"
    __ros_comment__ = "# An array of poses that represents a Path for a robot to follow."

    header: Header = Field(default_factory=Header)  # Indicates the frame_id of the path.
    poses: list[PoseStamped] = Field(default_factory=list)  # Array of poses to follow.


class MapMetaData(Message):
    """The size, resolution and placement of an occupancy grid."""

    __ros_type__ = "nav_msgs/msg/MapMetaData"
    __ros_comment__ = "# This hold basic information about the characteristics of the OccupancyGrid"

    map_load_time: Time = Field(default_factory=Time)  # The time at which the map was loaded
    resolution: Float32 = 0.0  # The map resolution [m/cell]
    width: UInt32 = 0  # Map width [cells]
    height: UInt32 = 0  # Map height [cells]
    # The origin of the map [m, m, rad]: the real-world pose of cell (0,0).
    origin: Pose = Field(default_factory=Pose)


class OccupancyGrid(Message):
    """A 2D grid map: ``data`` row-major from cell (0, 0), each cell an occupancy probability in
    0..100, or -1 for unknown."""

    __ros_type__ = "nav_msgs/msg/OccupancyGrid"
    __ros_comment__ = "# This represents a 2-D grid map"

    header: Header = Field(default_factory=Header)
    info: MapMetaData = Field(default_factory=MapMetaData)  # MetaData for the map
    data: list[Int8] = Field(default_factory=list)  # row-major, occupancy in [0,100], -1 unknown
