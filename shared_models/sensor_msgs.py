"""sensor_msgs: laser scans, images, cameras, IMUs, point clouds, joint states and range readings.

Non-finite numbers are refused here as in every Skydeck message: a beam with no return is 0.0 in
``LaserScan.ranges``, as the Neato driver publishes it (not ROS's +Inf).
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import ConfigDict, Field

from shared_models._message import (
    Bool,
    Float32,
    Float64,
    Message,
    String,
    UInt8,
    UInt8Array,
    UInt32,
    fixed_floats,
)
from shared_models.geometry_msgs import Quaternion, Vector3
from shared_models.std_msgs import Header

__all__ = [
    "CameraInfo",
    "CompressedImage",
    "Image",
    "Imu",
    "JointState",
    "LaserScan",
    "PointCloud2",
    "PointField",
    "Range",
    "RegionOfInterest",
]

# uint8[] travels as base64 in JSON, as rosbridge does: a JSON array of ints would be 3-4x bigger.
# UInt8Array writes the standard alphabet and also accepts a list of ints or, from Python, base64.
_BYTES_AS_BASE64 = ConfigDict(ser_json_bytes="base64", val_json_bytes="base64")


class CompressedImage(Message):
    """A compressed image (JPEG or PNG bytes); ``data`` travels in JSON as base64.

    Example::

        CompressedImage(header=Header(frame_id="camera"), format="jpeg", data=jpeg_bytes)
    """

    model_config = _BYTES_AS_BASE64

    __ros_type__ = "sensor_msgs/msg/CompressedImage"
    __ros_comment__ = (
        "# This message contains a compressed image.\n"
        "# format: the image format, e.g. jpeg or png.\n"
        "# data: the compressed image buffer (base64 in JSON)."
    )

    header: Header = Field(default_factory=Header)
    format: String = ""
    data: UInt8Array = b""


class Image(Message):
    """An uncompressed image: ``height`` rows of ``step`` bytes each, pixels as ``encoding`` says
    (``rgb8``, ``bgr8``, ``mono8``...); ``data`` travels in JSON as base64."""

    model_config = _BYTES_AS_BASE64

    __ros_type__ = "sensor_msgs/msg/Image"
    __ros_comment__ = (
        "# This message contains an uncompressed image\n"
        "# (0, 0) is at top-left corner of image"
    )

    header: Header = Field(default_factory=Header)
    height: UInt32 = 0  # image height, that is, number of rows
    width: UInt32 = 0  # image width, that is, number of columns
    encoding: String = ""  # encoding of pixels: channel meaning, ordering, size
    is_bigendian: UInt8 = 0  # is this data bigendian?
    step: UInt32 = 0  # full row length in bytes
    data: UInt8Array = b""  # actual matrix data, size is (step * rows)


class LaserScan(Message):
    """One sweep of a planar laser range-finder: ``ranges[i]`` is the distance along the beam at
    ``angle_min + i * angle_increment`` (radians, counter-clockwise, 0 straight ahead).

    Skydeck's scans put 0.0 where a beam has no return, as the Neato driver does, so course code
    that checks ``if msg.ranges[0] != 0.0`` works; NaN and inf are refused.
    """

    __ros_type__ = "sensor_msgs/msg/LaserScan"
    __ros_comment__ = (
        "# Single scan from a planar laser range-finder\n"
        "#\n"
        "# If you have another ranging device with different behavior (e.g. a sonar\n"
        "# array), please find or create a different message, since applications\n"
        "# will make fairly laser-specific assumptions about this data"
    )

    header: Header = Field(default_factory=Header)
    angle_min: Float32 = 0.0  # start angle of the scan [rad]
    angle_max: Float32 = 0.0  # end angle of the scan [rad]
    angle_increment: Float32 = 0.0  # angular distance between measurements [rad]
    time_increment: Float32 = 0.0  # time between measurements [seconds]
    scan_time: Float32 = 0.0  # time between scans [seconds]
    range_min: Float32 = 0.0  # minimum range value [m]
    range_max: Float32 = 0.0  # maximum range value [m]
    ranges: list[Float32] = Field(default_factory=list)  # range data [m]
    intensities: list[Float32] = Field(default_factory=list)  # device-specific units


class Imu(Message):
    """An inertial measurement: orientation, angular velocity and linear acceleration, each with a
    row-major 3x3 covariance (9 numbers; all zeros means "unknown", -1 first "not provided")."""

    __ros_type__ = "sensor_msgs/msg/Imu"
    __ros_comment__ = (
        "# This is a message to hold data from an IMU (Inertial Measurement Unit)\n"
        "#\n"
        "# Accelerations are in m/s^2 (not in g's), rotational velocity in rad/sec.\n"
        "# A covariance of all zeros means \"covariance unknown\"; -1 in element 0 of a\n"
        "# covariance means the device gives no estimate of that quantity."
    )

    header: Header = Field(default_factory=Header)
    orientation: Quaternion = Field(default_factory=Quaternion)
    orientation_covariance: list[Float64] = fixed_floats(9)  # Row major about x, y, z axes
    angular_velocity: Vector3 = Field(default_factory=Vector3)
    angular_velocity_covariance: list[Float64] = fixed_floats(9)  # Row major about x, y, z axes
    linear_acceleration: Vector3 = Field(default_factory=Vector3)
    linear_acceleration_covariance: list[Float64] = fixed_floats(9)  # Row major x, y z


class RegionOfInterest(Message):
    """A rectangle of an image (a camera's region of interest)."""

    __ros_type__ = "sensor_msgs/msg/RegionOfInterest"
    __ros_comment__ = (
        "# This message is used to specify a region of interest within an image.\n"
        "#\n"
        "# When used to specify the ROI setting of the camera when the image was\n"
        "# taken, the height and width fields should either match the height and\n"
        "# width fields for the associated image; or height = width = 0\n"
        "# indicates that the full resolution image was captured."
    )

    x_offset: UInt32 = 0  # Leftmost pixel of the ROI
    y_offset: UInt32 = 0  # Topmost pixel of the ROI
    height: UInt32 = 0  # Height of ROI
    width: UInt32 = 0  # Width of ROI
    do_rectify: Bool = False  # True if a distinct rectified ROI should be calculated


class CameraInfo(Message):
    """A camera's calibration: image size, distortion ``d``, intrinsics ``k`` (3x3), rectification
    ``r`` (3x3) and projection ``p`` (3x4), row-major; ROS 2 spells them in lower case."""

    __ros_type__ = "sensor_msgs/msg/CameraInfo"
    __ros_comment__ = (
        "# This message defines meta information for a camera: its image size,\n"
        "# distortion model and parameters (d), intrinsic camera matrix (k),\n"
        "# rectification matrix (r) and projection matrix (p)."
    )

    header: Header = Field(default_factory=Header)
    height: UInt32 = 0
    width: UInt32 = 0
    distortion_model: String = ""
    d: list[Float64] = Field(default_factory=list)
    k: list[Float64] = fixed_floats(9)  # 3x3 row-major matrix
    r: list[Float64] = fixed_floats(9)  # 3x3 row-major matrix
    p: list[Float64] = fixed_floats(12)  # 3x4 row-major matrix
    binning_x: UInt32 = 0
    binning_y: UInt32 = 0
    roi: RegionOfInterest = Field(default_factory=RegionOfInterest)


class PointField(Message):
    """One field of a PointCloud2 point: name, byte offset, ``datatype`` (a constant) and count."""

    __ros_type__ = "sensor_msgs/msg/PointField"
    __ros_comment__ = (
        "# This message holds the description of one point entry in the\n"
        "# PointCloud2 message format."
    )
    __ros_constants__ = (
        "INT8",
        "UINT8",
        "INT16",
        "UINT16",
        "INT32",
        "UINT32",
        "FLOAT32",
        "FLOAT64",
    )

    INT8: ClassVar[UInt8] = 1
    UINT8: ClassVar[UInt8] = 2
    INT16: ClassVar[UInt8] = 3
    UINT16: ClassVar[UInt8] = 4
    INT32: ClassVar[UInt8] = 5
    UINT32: ClassVar[UInt8] = 6
    FLOAT32: ClassVar[UInt8] = 7
    FLOAT64: ClassVar[UInt8] = 8

    name: String = ""  # Name of field
    offset: UInt32 = 0  # Offset from start of point struct
    datatype: UInt8 = 0  # Datatype enumeration, see above
    count: UInt32 = 0  # How many elements in the field


class PointCloud2(Message):
    """A point cloud: ``height`` x ``width`` points of ``point_step`` bytes, laid out by
    ``fields``; ``data`` travels in JSON as base64."""

    model_config = _BYTES_AS_BASE64

    __ros_type__ = "sensor_msgs/msg/PointCloud2"
    __ros_comment__ = (
        "# This message holds a collection of N-dimensional points, which may\n"
        "# contain additional information such as normals, intensity, etc. The\n"
        "# point data is stored as a binary blob, its layout described by the\n"
        "# contents of the \"fields\" array."
    )

    header: Header = Field(default_factory=Header)
    height: UInt32 = 0  # 2D structure of the point cloud: 1 row if the cloud is unordered
    width: UInt32 = 0
    fields: list[PointField] = Field(default_factory=list)  # the channels and their layout
    is_bigendian: Bool = False  # Is this data bigendian?
    point_step: UInt32 = 0  # Length of a point in bytes
    row_step: UInt32 = 0  # Length of a row in bytes
    data: UInt8Array = b""  # Actual point data, size is (row_step*height)
    is_dense: Bool = False  # True if there are no invalid points


class JointState(Message):
    """The state of named joints: position, velocity and effort, each list empty or as long as
    ``name``."""

    __ros_type__ = "sensor_msgs/msg/JointState"
    __ros_comment__ = (
        "# This is a message that holds data to describe the state of a set of torque\n"
        "# controlled joints.\n"
        "#\n"
        "# The state of each joint (revolute or prismatic) is defined by:\n"
        "#  * the position of the joint (rad or m),\n"
        "#  * the velocity of the joint (rad/s or m/s) and\n"
        "#  * the effort that is applied in the joint (Nm or N)."
    )

    header: Header = Field(default_factory=Header)
    name: list[String] = Field(default_factory=list)
    position: list[Float64] = Field(default_factory=list)
    velocity: list[Float64] = Field(default_factory=list)
    effort: list[Float64] = Field(default_factory=list)


class Range(Message):
    """One reading of a single-beam ranger (ultrasound or infrared), as Humble defines it.

    ROS lets fixed-distance rangers send -Inf/+Inf in ``range``; Skydeck refuses non-finite
    numbers, so such a sensor reports ``min_range`` or ``max_range`` instead.
    """

    __ros_type__ = "sensor_msgs/msg/Range"
    __ros_comment__ = (
        "# Single range reading from an active ranger that emits energy and reports\n"
        "# one range reading that is valid along an arc at the distance measured.\n"
        "# This message is  not appropriate for laser scanners. See the LaserScan\n"
        "# message if you are working with a laser scanner."
    )
    __ros_constants__ = ("ULTRASOUND", "INFRARED")

    ULTRASOUND: ClassVar[UInt8] = 0
    INFRARED: ClassVar[UInt8] = 1

    header: Header = Field(default_factory=Header)
    radiation_type: UInt8 = 0  # the type of radiation used by the sensor (sound, IR, etc) [enum]
    field_of_view: Float32 = 0.0  # the size of the arc that the distance reading is valid for [rad]
    min_range: Float32 = 0.0  # minimum range value [m]
    max_range: Float32 = 0.0  # maximum range value [m]
    range: Float32 = 0.0  # range data [m]
