"""Looking types up by name and printing them as `ros2 interface show` does."""

from __future__ import annotations

import pytest

from shared_models import (
    Message,
    UnknownInterfaceError,
    all_interfaces,
    get_interface,
    interface_names,
    interface_text,
)
from shared_models.catalogue import MESSAGE_PACKAGES
from shared_models.geometry_msgs import PoseStamped
from shared_models.std_srvs import Trigger, TriggerRequest


def test_get_interface_accepts_ros2_ros1_and_srv_forms() -> None:
    assert get_interface("geometry_msgs/msg/PoseStamped") is PoseStamped
    assert get_interface("geometry_msgs/PoseStamped") is PoseStamped
    assert get_interface("std_srvs/srv/Trigger") is Trigger
    assert get_interface("std_srvs/Trigger") is Trigger
    assert get_interface("std_srvs/srv/Trigger_Request") is TriggerRequest
    # ROS 1 form with the same short name in two kinds: std_msgs has a message Empty only.
    assert get_interface("std_msgs/Empty").__ros_type__ == "std_msgs/msg/Empty"
    assert get_interface("std_srvs/Empty").__ros_type__ == "std_srvs/srv/Empty"


def test_unknown_interface_suggests_close_matches() -> None:
    with pytest.raises(UnknownInterfaceError) as caught:
        get_interface("geometry_msgs/msg/PoseStampd")
    message = str(caught.value)
    assert "'geometry_msgs/msg/PoseStampd'" in message
    assert "did you mean geometry_msgs/msg/PoseStamped" in message
    assert "skydeck interface list" in message
    assert "\n" not in message  # callers show the first line only
    assert isinstance(caught.value, LookupError)


def test_unknown_bare_name_suggests_the_full_one() -> None:
    with pytest.raises(UnknownInterfaceError) as caught:
        get_interface("PointStamped")
    assert caught.value.suggestions[0] == "geometry_msgs/msg/PointStamped"


def test_unknown_without_match_still_points_at_the_list() -> None:
    with pytest.raises(UnknownInterfaceError, match="skydeck interface list") as caught:
        get_interface("zzz_msgs/msg/Nothing")
    assert caught.value.suggestions == []


def test_interface_names() -> None:
    names = interface_names()
    assert names == sorted(names)
    assert "geometry_msgs/msg/PointStamped" in names
    assert "std_srvs/srv/Trigger" in names
    assert not [name for name in names if name.endswith(("_Request", "_Response"))]
    assert {"rosapi_msgs/srv/Topics", "rosapi_msgs/srv/GetTime"} <= set(interface_names("srv"))
    python_declared = [name for name in interface_names("srv") if name.split("/")[0] in MESSAGE_PACKAGES]
    assert [name for name in python_declared if not name.startswith("rosapi_msgs/")] == [
        "rcl_interfaces/srv/DescribeParameters",
        "rcl_interfaces/srv/GetParameterTypes",
        "rcl_interfaces/srv/GetParameters",
        "rcl_interfaces/srv/ListParameters",
        "rcl_interfaces/srv/SetParameters",
        "rcl_interfaces/srv/SetParametersAtomically",
        "ros_workshop/srv/FlyCommand",
        "skydeck_launch/srv/KillNode",
        "skydeck_opencv/srv/WindowInput",
        "std_srvs/srv/Empty",
        "std_srvs/srv/SetBool",
        "std_srvs/srv/Trigger",
    ]
    assert all("/msg/" in name for name in interface_names("msg"))
    assert "example_interfaces/srv/AddTwoInts" in interface_names("srv")  # shipped as definition files
    assert interface_names("action")[:1] == ["actionlib/action/Test"]
    assert sorted(interface_names("msg") + interface_names("srv") + interface_names("action")) == names
    with pytest.raises(ValueError, match="kind"):
        interface_names("actions")


POINT_STAMPED = """\
# This represents a Point with reference coordinate frame and timestamp

std_msgs/Header header
\tuint32 seq
\tbuiltin_interfaces/Time stamp
\t\tint32 sec
\t\tuint32 nanosec
\tstring frame_id
Point point
\tfloat64 x
\tfloat64 y
\tfloat64 z"""


def test_show_point_stamped_as_ros2() -> None:
    assert interface_text("geometry_msgs/msg/PointStamped") == POINT_STAMPED
    assert interface_text(get_interface("geometry_msgs/PointStamped")) == POINT_STAMPED


def test_show_service() -> None:
    assert interface_text("std_srvs/srv/Trigger") == "---\nbool success\nstring message"
    assert interface_text("ros_workshop/srv/FlyCommand") == (
        "float32 x\nfloat32 y\n---\nbool success\nstring message"
    )


def test_show_arrays_and_defaults() -> None:
    assert interface_text("geometry_msgs/msg/PoseArray") == (
        "# An array of poses with a header for global reference.\n"
        "\n"
        "std_msgs/Header header\n"
        "\tuint32 seq\n"
        "\tbuiltin_interfaces/Time stamp\n"
        "\t\tint32 sec\n"
        "\t\tuint32 nanosec\n"
        "\tstring frame_id\n"
        "Pose[] poses\n"
        "\tPoint position\n"
        "\t\tfloat64 x\n"
        "\t\tfloat64 y\n"
        "\t\tfloat64 z\n"
        "\tQuaternion orientation\n"
        "\t\tfloat64 x\n"
        "\t\tfloat64 y\n"
        "\t\tfloat64 z\n"
        "\t\tfloat64 w 1"
    )
    text = interface_text("ros_workshop/msg/AiStatus")
    assert "\nint32[] visited\n" in text
    assert "\nint32 target -1\n" in text
    assert '\nstring state "idle"\n' in text
    assert "\nuint8[] data" in interface_text("sensor_msgs/msg/CompressedImage")
    assert "\nPoint32[] points\n" in interface_text("geometry_msgs/msg/Polygon")


def test_show_constants_before_fields() -> None:
    text = interface_text("rcl_interfaces/msg/Log")
    constants = "uint8 DEBUG=10\nuint8 INFO=20\nuint8 WARN=30\nuint8 ERROR=40\nuint8 FATAL=50\n"
    assert constants + "\nbuiltin_interfaces/Time stamp\n\tint32 sec\n" in text
    text = interface_text("mavros_msgs/msg/PositionTarget")
    assert "uint8 FRAME_LOCAL_NED=1\n" in text
    assert "uint16 IGNORE_YAW_RATE=2048\n" in text
    assert text.index("IGNORE_YAW_RATE=2048") < text.index("std_msgs/Header header")
    assert "\ngeometry_msgs/Point position\n\tfloat64 x\n" in text
    assert "\nfloat32 yaw\nfloat32 yaw_rate" in text


@pytest.mark.parametrize("name", sorted(all_interfaces()))
def test_every_interface_has_show_text(name: str) -> None:
    text = interface_text(name)
    cls = get_interface(name)
    if isinstance(cls, type) and issubclass(cls, Message):
        top_level = [line for line in text.splitlines() if line and line[0] not in "#\t"]
        assert [line.split()[1].split("=")[0] for line in top_level] == [
            *cls.__ros_constants__,
            *cls.model_fields,
        ]


def test_a_field_without_ros_type_is_reported() -> None:
    class Untyped(Message):
        value: int = 0

    with pytest.raises(TypeError, match="field value has no ROS type"):
        interface_text(Untyped)


HEADER = """\
std_msgs/Header header
\tuint32 seq
\tbuiltin_interfaces/Time stamp
\t\tint32 sec
\t\tuint32 nanosec
\tstring frame_id"""


def test_show_laser_scan() -> None:
    text = interface_text("sensor_msgs/msg/LaserScan")
    assert text.startswith("# Single scan from a planar laser range-finder\n")
    fields = text.split("\n\n", 1)[1]
    assert fields == HEADER + (
        "\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\nfloat32 time_increment"
        "\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max"
        "\nfloat32[] ranges\nfloat32[] intensities"
    )


def test_show_odometry_nests_across_packages_with_fixed_arrays() -> None:
    fields = interface_text("nav_msgs/msg/Odometry").split("\n\n", 1)[1]
    vector = "\t\t\tfloat64 x\n\t\t\tfloat64 y\n\t\t\tfloat64 z\n"
    assert fields == (
        HEADER + "\nstring child_frame_id\n"
        "geometry_msgs/PoseWithCovariance pose\n"
        "\tPose pose\n"
        "\t\tPoint position\n" + vector + "\t\tQuaternion orientation\n" + vector
        + "\t\t\tfloat64 w 1\n"
        "\tfloat64[36] covariance\n"
        "geometry_msgs/TwistWithCovariance twist\n"
        "\tTwist twist\n"
        "\t\tVector3 linear\n" + vector + "\t\tVector3 angular\n" + vector
        + "\tfloat64[36] covariance"
    )


def test_show_marker_constants_then_humble_fields() -> None:
    text = interface_text("visualization_msgs/msg/Marker")
    constants = "\n".join(
        f"int32 {name}={value}"
        for name, value in [
            ("ARROW", 0),
            ("CUBE", 1),
            ("SPHERE", 2),
            ("CYLINDER", 3),
            ("LINE_STRIP", 4),
            ("LINE_LIST", 5),
            ("CUBE_LIST", 6),
            ("SPHERE_LIST", 7),
            ("POINTS", 8),
            ("TEXT_VIEW_FACING", 9),
            ("MESH_RESOURCE", 10),
            ("TRIANGLE_LIST", 11),
            ("ADD", 0),
            ("MODIFY", 0),
            ("DELETE", 2),
            ("DELETEALL", 3),
        ]
    )
    assert "\n\n" + constants + "\n\n" + HEADER + "\nstring ns\nint32 id\nint32 type\n" in text
    for part in (
        "\nbuiltin_interfaces/Duration lifetime\n\tint32 sec\n\tuint32 nanosec\nbool frame_locked\n",
        "\ngeometry_msgs/Point[] points\n\tfloat64 x\n",
        "\nstd_msgs/ColorRGBA[] colors\n\tfloat32 r\n\tfloat32 g\n\tfloat32 b\n\tfloat32 a\n",
        "\nsensor_msgs/CompressedImage texture\n\tstd_msgs/Header header\n\t\tuint32 seq\n",
        "\n\tstring format\n\tuint8[] data\nUVCoordinate[] uv_coordinates\n\tfloat32 u\n\tfloat32 v\n",
        "\nstring text\nstring mesh_resource\nMeshFile mesh_file\n\tstring filename\n"
        "\tuint8[] data\nbool mesh_use_embedded_materials",
    ):
        assert part in text
    assert text.endswith("bool mesh_use_embedded_materials")


def test_show_parameter_types_bounds_and_declared_defaults() -> None:
    text = interface_text("rcl_interfaces/msg/ParameterDescriptor")
    assert "\nbool read_only false\nbool dynamic_typing false\n" in text
    assert "\nFloatingPointRange[<=1] floating_point_range\n\tfloat64 from_value\n" in text
    assert "\nIntegerRange[<=1] integer_range\n\tint64 from_value\n\tint64 to_value\n\tuint64 step" in text
    assert "\nbyte[] byte_array_value\nbool[] bool_array_value\n" in interface_text(
        "rcl_interfaces/msg/ParameterValue"
    )
    assert interface_text("rcl_interfaces/srv/ListParameters") == (
        "uint64 DEPTH_RECURSIVE=0\n\nstring[] prefixes\nuint64 depth\n---\n"
        "ListParametersResult result\n\tstring[] names\n\tstring[] prefixes"
    )
    assert "\nfloat64[9] k\nfloat64[9] r\nfloat64[12] p\n" in interface_text(
        "sensor_msgs/msg/CameraInfo"
    )
    assert interface_text("neato2_interfaces/msg/Bump") == (
        "uint8 left_front\nuint8 left_side\nuint8 right_front\nuint8 right_side"
    )
