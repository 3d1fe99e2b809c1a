"""Messages behave like ROS's in Python: positional construction as ROS 1 (genpy), defaults that
nest, mutation by attribute, lists appended in place, constants as class attributes, fixed-size
arrays, and populated messages that round-trip through the same JSON."""

from __future__ import annotations

import json
import math

import pytest
from pydantic import ValidationError

from shared_models import Message, all_interfaces
from shared_models.builtin_interfaces import Duration, Time
from shared_models.geometry_msgs import (
    Point,
    Point32,
    PointStamped,
    Polygon,
    Pose,
    PoseStamped,
    PoseWithCovariance,
    Quaternion,
    Transform,
    TransformStamped,
    Twist,
    TwistWithCovariance,
    Vector3,
)
from shared_models.nav_msgs import MapMetaData, OccupancyGrid, Odometry, Path
from shared_models.neato2_interfaces import Bump
from shared_models.rcl_interfaces import (
    GetParameterTypes,
    ListParameters,
    Parameter,
    ParameterDescriptor,
    ParameterEvent,
    ParameterType,
    ParameterValue,
    SetParametersResult,
)
from shared_models.sensor_msgs import (
    CameraInfo,
    Image,
    Imu,
    LaserScan,
    PointCloud2,
    PointField,
    Range,
)
from shared_models.std_msgs import (
    ColorRGBA,
    Empty,
    Float32MultiArray,
    Header,
    Int8,
    Int16,
    MultiArrayDimension,
    MultiArrayLayout,
    UInt64,
)
from shared_models.std_srvs import TriggerResponse
from shared_models.tf2_msgs import TFMessage
from shared_models.visualization_msgs import Marker, MarkerArray, MeshFile

MESSAGES = {name: cls for name, cls in all_interfaces().items() if issubclass(cls, Message)}


class TestPositionalConstruction:
    def test_seed_forms(self) -> None:
        assert Pose(Point(0, 0, 0), Quaternion(0, 0, 0, 1)) == Pose()
        assert Point(1, 2, 3) == Point(x=1.0, y=2.0, z=3.0)
        assert isinstance(Point(1, 2, 3).x, float)  # an int given for a float field is a float
        twist = Twist(Vector3(0.2, 0, 0), Vector3(0, 0, 0.5))
        assert (twist.linear.x, twist.angular.z) == (0.2, 0.5)
        assert TriggerResponse(True, "All ok!") == TriggerResponse(success=True, message="All ok!")
        header = Header(3, Time(1, 2), "odom")
        assert (header.seq, header.stamp.nanosec, header.frame_id) == (3, 2, "odom")

    def test_fewer_values_keep_the_other_defaults(self) -> None:
        # genpy needs every field; allowing fewer accepts all ROS 1 code and fills like keywords.
        assert Quaternion(0.5) == Quaternion(x=0.5, w=1.0)

    @pytest.mark.parametrize("ros_type", sorted(MESSAGES))
    def test_every_message_takes_its_fields_in_order(self, ros_type: str) -> None:
        cls = MESSAGES[ros_type]
        default = cls()
        values = [getattr(default, name) for name in cls.model_fields]
        assert cls(*values) == default
        with pytest.raises(TypeError, match=rf"{cls.__name__}\(\) takes at most {len(values)} "):
            cls(*values, 0)

    def test_too_many_says_which_fields(self) -> None:
        with pytest.raises(TypeError) as caught:
            Point(1, 2, 3, 4)
        assert str(caught.value) == (
            "Point() takes at most 3 positional arguments (x, y, z), 4 given"
        )
        with pytest.raises(TypeError, match=r"at most 1 positional argument \(points\), 2 given"):
            Polygon([], [])
        with pytest.raises(TypeError, match=r"Empty\(\) takes at most 0 positional arguments, 1"):
            Empty(1)

    def test_mixing_positional_and_keywords_is_refused_as_genpy_does(self) -> None:
        with pytest.raises(TypeError) as caught:
            Point(1, y=2)
        assert str(caught.value) == (
            "Point() takes positional or keyword arguments, not both (as ROS 1 messages): "
            "got 1 positional and y"
        )

    def test_positional_values_are_validated_like_keywords(self) -> None:
        with pytest.raises(ValidationError):
            Point(math.nan)
        with pytest.raises(ValidationError):
            Point("1.0")
        with pytest.raises(ValidationError):
            Bump(256)


class TestDefaultsAndMutation:
    def test_mutate_by_attribute(self) -> None:
        msg = Twist()
        msg.linear.x = 0.1
        msg.angular.z = -0.5
        assert json.loads(msg.model_dump_json()) == {
            "linear": {"x": 0.1, "y": 0.0, "z": 0.0},
            "angular": {"x": 0.0, "y": 0.0, "z": -0.5},
        }
        assert Twist().linear.x == 0.0  # the nested default is not shared

    def test_nested_defaults_reach_the_leaves(self) -> None:
        odom = Odometry()
        odom.pose.pose.position.x = 1.5
        odom.header.stamp.sec = 4
        assert odom.pose.pose.orientation.w == 1.0
        assert Odometry().pose.pose.position.x == 0.0
        marker = Marker()
        marker.scale.x = marker.scale.y = 0.1
        marker.color.a = 1.0
        assert (Marker().scale.x, Marker().color.a) == (0.0, 0.0)

    def test_lists_append_in_place(self) -> None:
        polygon = Polygon()
        polygon.points.append(Point32(x=1.0))
        polygon.points.append(Point32(1, 2, 0))
        assert [p.x for p in polygon.points] == [1.0, 1.0]
        assert Polygon().points == []
        path = Path()
        path.poses.append(PoseStamped())
        scan = LaserScan()
        scan.ranges.extend([1.0, 0.0, 2.5])
        assert json.loads(scan.model_dump_json())["ranges"] == [1.0, 0.0, 2.5]
        markers = MarkerArray()
        markers.markers.append(Marker(id=1))
        assert len(MarkerArray().markers) == 0

    def test_assignments_are_validated_as_rclpy_setters_are(self) -> None:
        msg = Twist()
        for bad in (math.nan, math.inf, "0.1", None):
            with pytest.raises(ValidationError):
                msg.linear.x = bad  # type: ignore[assignment]
        assert msg.linear.x == 0.0  # a refused value leaves the field as it was
        with pytest.raises(ValidationError):
            Bump().left_front = 2**8
        msg.linear.x = 1  # an int is a valid float
        assert isinstance(msg.linear.x, float)
        msg.angular = {"z": 0.5}  # type: ignore[assignment]  # a dict becomes the message
        assert msg.angular == Vector3(z=0.5)
        image = Image()
        image.data = [1, 2, 3]  # type: ignore[assignment]  # uint8[] as ROS spells it
        assert image.data == b"\x01\x02\x03"
        stamp = Time()
        with pytest.raises(ValidationError):
            stamp.secs = 2**31  # the ROS 1 alias writes through the validated field

    def test_unknown_attribute_is_refused(self) -> None:
        msg = Twist()
        with pytest.raises(ValueError, match="has no attribute .lineer."):
            msg.lineer = Vector3()  # type: ignore[attr-defined]


class TestConstants:
    def test_marker(self) -> None:
        types = [
            Marker.ARROW,
            Marker.CUBE,
            Marker.SPHERE,
            Marker.CYLINDER,
            Marker.LINE_STRIP,
            Marker.LINE_LIST,
            Marker.CUBE_LIST,
            Marker.SPHERE_LIST,
            Marker.POINTS,
            Marker.TEXT_VIEW_FACING,
            Marker.MESH_RESOURCE,
            Marker.TRIANGLE_LIST,
        ]
        assert types == list(range(12))
        assert (Marker.ADD, Marker.MODIFY, Marker.DELETE, Marker.DELETEALL) == (0, 0, 2, 3)

    def test_point_field_range_and_parameter_type(self) -> None:
        assert list(range(1, 9)) == [
            PointField.INT8,
            PointField.UINT8,
            PointField.INT16,
            PointField.UINT16,
            PointField.INT32,
            PointField.UINT32,
            PointField.FLOAT32,
            PointField.FLOAT64,
        ]
        assert (Range.ULTRASOUND, Range.INFRARED) == (0, 1)
        assert ParameterType.PARAMETER_NOT_SET == 0
        assert ParameterType.PARAMETER_DOUBLE == 3
        assert ParameterType.PARAMETER_STRING_ARRAY == 9
        assert ListParameters.Request.DEPTH_RECURSIVE == 0

    def test_constants_are_not_fields(self) -> None:
        assert json.loads(Marker().model_dump_json()).keys().isdisjoint({"ARROW", "DELETEALL"})
        assert "FLOAT32" not in PointField.model_fields
        assert json.loads(ParameterType().model_dump_json()) == {}
        with pytest.raises(AttributeError, match="ClassVar"):
            Marker().ARROW = 5  # type: ignore[misc]


class TestFixedSizeArrays:
    @pytest.mark.parametrize(
        ("cls", "field", "length"),
        [
            (PoseWithCovariance, "covariance", 36),
            (TwistWithCovariance, "covariance", 36),
            (Imu, "orientation_covariance", 9),
            (Imu, "angular_velocity_covariance", 9),
            (Imu, "linear_acceleration_covariance", 9),
            (CameraInfo, "k", 9),
            (CameraInfo, "r", 9),
            (CameraInfo, "p", 12),
        ],
    )
    def test_zeros_by_default_and_no_other_length(self, cls, field: str, length: int) -> None:
        assert getattr(cls(), field) == [0.0] * length
        assert getattr(cls(), field) is not getattr(cls(), field)
        values = [float(i) for i in range(length)]
        assert getattr(cls.model_validate({field: values}), field) == values
        for wrong in (length - 1, length + 1, 0):
            with pytest.raises(ValidationError, match=field):
                cls.model_validate({field: [0.0] * wrong})
        with pytest.raises(ValidationError):
            cls.model_validate_json(json.dumps({field: [0.0] * (length + 1)}))

    def test_bounded_arrays(self) -> None:
        from shared_models.rcl_interfaces import FloatingPointRange

        one = ParameterDescriptor(floating_point_range=[FloatingPointRange(to_value=1.0)])
        assert one.floating_point_range[0].to_value == 1.0
        with pytest.raises(ValidationError, match="floating_point_range"):
            ParameterDescriptor(floating_point_range=[FloatingPointRange()] * 2)

    def test_camera_info_d_is_any_length(self) -> None:
        assert CameraInfo(d=[0.1, 0.2, 0.0, 0.0, 0.0]).d[0] == 0.1


class TestIntegerRanges:
    @pytest.mark.parametrize(
        ("cls", "good", "bad"),
        [(Int8, -128, 128), (Int16, -(2**15), 2**15), (UInt64, 2**64 - 1, 2**64), (Bump, 1, -1)],
    )
    def test_limits(self, cls: type[Message], good: int, bad: int) -> None:
        field = next(iter(cls.model_fields))
        assert getattr(cls.model_validate({field: good}), field) == good
        with pytest.raises(ValidationError):
            cls.model_validate({field: bad})


def _scan() -> LaserScan:
    return LaserScan(
        header=Header(stamp=Time(sec=3, nanosec=200), frame_id="base_laser_link"),
        angle_min=0.0,
        angle_max=2 * math.pi,
        angle_increment=math.radians(1),
        scan_time=0.2,
        range_min=0.2,
        range_max=5.0,
        ranges=[1.25] * 359 + [0.0],
    )


POPULATED: list[Message] = [
    _scan(),
    Odometry(
        header=Header(frame_id="odom"),
        child_frame_id="base_link",
        pose=PoseWithCovariance(pose=Pose(Point(1, 2, 0), Quaternion(0, 0, 0.38, 0.92))),
        twist=TwistWithCovariance(twist=Twist(Vector3(0.3, 0, 0), Vector3(0, 0, 1.0))),
    ),
    TFMessage(
        transforms=[
            TransformStamped(
                header=Header(frame_id="odom"),
                child_frame_id="base_link",
                transform=Transform(Vector3(1, 0, 0), Quaternion()),
            )
        ]
    ),
    MarkerArray(
        markers=[
            Marker(
                header=Header(frame_id="map"),
                ns="boxes",
                id=7,
                type=Marker.LINE_STRIP,
                points=[Point(0, 0, 0), Point(1, 1, 0)],
                colors=[ColorRGBA(1, 0, 0, 1), ColorRGBA(0, 1, 0, 1)],
                lifetime=Duration(sec=2),
                mesh_file=MeshFile(filename="box.stl", data=b"solid\x00\xff"),
            ),
            Marker(action=Marker.DELETEALL),
        ]
    ),
    Image(height=2, width=3, encoding="rgb8", step=9, data=bytes(range(18))),
    PointCloud2(
        height=1,
        width=2,
        fields=[PointField(name="x", offset=0, datatype=PointField.FLOAT32, count=1)],
        point_step=4,
        row_step=8,
        data=b"\x00\x00\x80?\x00\x00\x00@",
        is_dense=True,
    ),
    CameraInfo(height=480, width=640, distortion_model="plumb_bob", d=[0.0] * 5),
    OccupancyGrid(info=MapMetaData(resolution=0.05, width=2, height=2), data=[-1, 0, 100, 50]),
    Float32MultiArray(
        layout=MultiArrayLayout(dim=[MultiArrayDimension(label="x", size=2, stride=2)]),
        data=[0.5, -1.5],
    ),
    ParameterEvent(
        node="/wall_follower",
        changed_parameters=[
            Parameter(name="speed", value=ParameterValue(type=3, double_value=0.2)),
            Parameter(name="raw", value=ParameterValue(type=5, byte_array_value=b"\x01\x02")),
        ],
    ),
    SetParametersResult(successful=False, reason="speed must be positive"),
    GetParameterTypes.Response(types=bytes([3, 4, 0])),
    Bump(left_front=1),
]


@pytest.mark.parametrize("msg", POPULATED, ids=lambda msg: type(msg).__name__)
def test_populated_messages_round_trip(msg: Message) -> None:
    cls = type(msg)
    text = msg.model_dump_json()
    assert cls.model_validate_json(text) == msg
    assert cls.model_validate(json.loads(text)) == msg  # a JSON-decoded dict, as `topic pub` gives
    assert cls.model_validate(msg.model_dump()) == msg


def test_byte_fields_are_base64_in_json() -> None:
    frame = json.loads(Image(data=b"\x00\xff\x10").model_dump_json())
    assert frame["data"] == "AP8Q"
    value = json.loads(ParameterValue(byte_array_value=b"\x01\x02").model_dump_json())
    assert value["byte_array_value"] == "AQI="
    assert json.loads(GetParameterTypes.Response(types=b"\x03").model_dump_json()) == {
        "types": "Aw=="
    }


@pytest.mark.parametrize(
    "frame",
    [
        '{"ranges": [1.0, NaN]}',
        '{"ranges": [Infinity]}',
        '{"range_max": -Infinity}',
    ],
)
def test_scan_refuses_non_finite_numbers(frame: str) -> None:
    with pytest.raises(ValidationError):
        LaserScan.model_validate_json(frame)
    with pytest.raises(ValidationError):
        LaserScan(ranges=[math.inf])
    with pytest.raises(ValidationError):
        Range(range=math.inf)


def test_a_message_prints_as_rclpy_prints_it() -> None:
    stamped = PointStamped(header=Header(frame_id="odom"), point=Point(1.0, 2.0, 0.0))
    assert repr(stamped.point) == "geometry_msgs.msg.Point(x=1.0, y=2.0, z=0.0)"
    assert str(stamped).startswith("geometry_msgs.msg.PointStamped(header=std_msgs.msg.Header(")
    assert "frame_id='odom'" in str(stamped) and str(stamped).endswith("point=geometry_msgs.msg.Point(x=1.0, y=2.0, z=0.0))")
    assert repr(TriggerResponse(success=True)) == "std_srvs.srv.Trigger_Response(success=True, message='')"
