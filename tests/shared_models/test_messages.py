"""Messages: ROS field names, defaults, JSON round trips and validation."""

from __future__ import annotations

import base64
import json
import math

import pytest
from pydantic import ValidationError

import shared_models
from shared_models import Message, ServiceType, all_interfaces
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import (
    Point,
    Point32,
    PointStamped,
    Polygon,
    Quaternion,
)
from shared_models.mavros_msgs import PositionTarget, State
from shared_models.rcl_interfaces import Log
from shared_models.ros_workshop import AiStatus, ControlState, FlyCommand
from shared_models.sensor_msgs import CompressedImage
from shared_models.std_msgs import Header
from shared_models.std_srvs import SetBool, Trigger, TriggerRequest, TriggerResponse

# The ROS field names in .msg order, written out independently of the models so that a renamed
# or reordered field fails here.
ROS_FIELDS: dict[str, list[str]] = {
    "builtin_interfaces/msg/Time": ["sec", "nanosec"],
    "builtin_interfaces/msg/Duration": ["sec", "nanosec"],
    "std_msgs/msg/Header": ["seq", "stamp", "frame_id"],
    "std_msgs/msg/String": ["data"],
    "std_msgs/msg/Bool": ["data"],
    "std_msgs/msg/Int32": ["data"],
    "std_msgs/msg/Float64": ["data"],
    "std_msgs/msg/Empty": [],
    "geometry_msgs/msg/Point": ["x", "y", "z"],
    "geometry_msgs/msg/Point32": ["x", "y", "z"],
    "geometry_msgs/msg/Vector3": ["x", "y", "z"],
    "geometry_msgs/msg/Quaternion": ["x", "y", "z", "w"],
    "geometry_msgs/msg/Pose": ["position", "orientation"],
    "geometry_msgs/msg/PoseStamped": ["header", "pose"],
    "geometry_msgs/msg/PoseArray": ["header", "poses"],
    "geometry_msgs/msg/Polygon": ["points"],
    "geometry_msgs/msg/PointStamped": ["header", "point"],
    "geometry_msgs/msg/Twist": ["linear", "angular"],
    "geometry_msgs/msg/TwistStamped": ["header", "twist"],
    "sensor_msgs/msg/CompressedImage": ["header", "format", "data"],
    "rcl_interfaces/msg/Log": ["stamp", "level", "name", "msg", "file", "function", "line"],
    "mavros_msgs/msg/State": [
        "header",
        "connected",
        "armed",
        "guided",
        "manual_input",
        "mode",
        "system_status",
    ],
    "mavros_msgs/msg/PositionTarget": [
        "header",
        "coordinate_frame",
        "type_mask",
        "position",
        "velocity",
        "acceleration_or_force",
        "yaw",
        "yaw_rate",
    ],
    "std_srvs/srv/Trigger_Request": [],
    "std_srvs/srv/Trigger_Response": ["success", "message"],
    "std_srvs/srv/Empty_Request": [],
    "std_srvs/srv/Empty_Response": [],
    "std_srvs/srv/SetBool_Request": ["data"],
    "std_srvs/srv/SetBool_Response": ["success", "message"],
    "ros_workshop/srv/FlyCommand_Request": ["x", "y"],
    "ros_workshop/srv/FlyCommand_Response": ["success", "message"],
    "skydeck_launch/srv/KillNode_Request": ["node"],
    "skydeck_launch/srv/KillNode_Response": ["success", "message", "reason"],
    "skydeck_opencv/msg/Trackbar": ["name", "value", "minimum", "maximum"],
    "skydeck_opencv/msg/Window": [
        "name",
        "title",
        "topic",
        "width",
        "height",
        "display_width",
        "display_height",
        "mouse",
        "trackbars",
    ],
    "skydeck_opencv/msg/Windows": ["windows"],
    "skydeck_opencv/srv/WindowInput_Request": ["window", "kind", "key", "event", "x", "y", "flags", "trackbar", "value"],
    "skydeck_opencv/srv/WindowInput_Response": ["success", "message"],
    "ros_workshop/msg/AiStatus": [
        "header",
        "state",
        "message",
        "visited",
        "target",
        "remaining",
        "tour",
        "tour_length",
    ],
    "ros_workshop/msg/ControlState": ["header", "state", "setpoint", "message"],
    "ros_workshop/msg/SimWorld": ["header", "id", "seed", "build", "boxes", "world", "namespaces"],
    # std_msgs
    "std_msgs/msg/ColorRGBA": ["r", "g", "b", "a"],
    "std_msgs/msg/Float32": ["data"],
    "std_msgs/msg/Int8": ["data"],
    "std_msgs/msg/Int16": ["data"],
    "std_msgs/msg/Int64": ["data"],
    "std_msgs/msg/UInt8": ["data"],
    "std_msgs/msg/UInt16": ["data"],
    "std_msgs/msg/UInt32": ["data"],
    "std_msgs/msg/UInt64": ["data"],
    "std_msgs/msg/MultiArrayDimension": ["label", "size", "stride"],
    "std_msgs/msg/MultiArrayLayout": ["dim", "data_offset"],
    "std_msgs/msg/Float32MultiArray": ["layout", "data"],
    "std_msgs/msg/Float64MultiArray": ["layout", "data"],
    "std_msgs/msg/Int32MultiArray": ["layout", "data"],
    # geometry_msgs
    "geometry_msgs/msg/Transform": ["translation", "rotation"],
    "geometry_msgs/msg/TransformStamped": ["header", "child_frame_id", "transform"],
    "geometry_msgs/msg/PoseWithCovariance": ["pose", "covariance"],
    "geometry_msgs/msg/PoseWithCovarianceStamped": ["header", "pose"],
    "geometry_msgs/msg/TwistWithCovariance": ["twist", "covariance"],
    "geometry_msgs/msg/TwistWithCovarianceStamped": ["header", "twist"],
    "geometry_msgs/msg/PolygonStamped": ["header", "polygon"],
    "geometry_msgs/msg/Vector3Stamped": ["header", "vector"],
    "geometry_msgs/msg/QuaternionStamped": ["header", "quaternion"],
    "geometry_msgs/msg/Pose2D": ["x", "y", "theta"],
    "geometry_msgs/msg/Accel": ["linear", "angular"],
    "geometry_msgs/msg/AccelStamped": ["header", "accel"],
    "geometry_msgs/msg/Wrench": ["force", "torque"],
    "geometry_msgs/msg/WrenchStamped": ["header", "wrench"],
    # sensor_msgs
    "sensor_msgs/msg/LaserScan": [
        "header",
        "angle_min",
        "angle_max",
        "angle_increment",
        "time_increment",
        "scan_time",
        "range_min",
        "range_max",
        "ranges",
        "intensities",
    ],
    "sensor_msgs/msg/Image": [
        "header",
        "height",
        "width",
        "encoding",
        "is_bigendian",
        "step",
        "data",
    ],
    "sensor_msgs/msg/Imu": [
        "header",
        "orientation",
        "orientation_covariance",
        "angular_velocity",
        "angular_velocity_covariance",
        "linear_acceleration",
        "linear_acceleration_covariance",
    ],
    "sensor_msgs/msg/RegionOfInterest": ["x_offset", "y_offset", "height", "width", "do_rectify"],
    "sensor_msgs/msg/CameraInfo": [
        "header",
        "height",
        "width",
        "distortion_model",
        "d",
        "k",
        "r",
        "p",
        "binning_x",
        "binning_y",
        "roi",
    ],
    "sensor_msgs/msg/PointField": ["name", "offset", "datatype", "count"],
    "sensor_msgs/msg/PointCloud2": [
        "header",
        "height",
        "width",
        "fields",
        "is_bigendian",
        "point_step",
        "row_step",
        "data",
        "is_dense",
    ],
    "sensor_msgs/msg/JointState": ["header", "name", "position", "velocity", "effort"],
    "sensor_msgs/msg/Range": [
        "header",
        "radiation_type",
        "field_of_view",
        "min_range",
        "max_range",
        "range",
    ],
    # nav_msgs
    "nav_msgs/msg/Odometry": ["header", "child_frame_id", "pose", "twist"],
    "nav_msgs/msg/Path": ["header", "poses"],
    "nav_msgs/msg/MapMetaData": ["map_load_time", "resolution", "width", "height", "origin"],
    "nav_msgs/msg/OccupancyGrid": ["header", "info", "data"],
    # visualization_msgs (Humble)
    "visualization_msgs/msg/UVCoordinate": ["u", "v"],
    "visualization_msgs/msg/MeshFile": ["filename", "data"],
    "visualization_msgs/msg/Marker": [
        "header",
        "ns",
        "id",
        "type",
        "action",
        "pose",
        "scale",
        "color",
        "lifetime",
        "frame_locked",
        "points",
        "colors",
        "texture_resource",
        "texture",
        "uv_coordinates",
        "text",
        "mesh_resource",
        "mesh_file",
        "mesh_use_embedded_materials",
    ],
    "visualization_msgs/msg/MarkerArray": ["markers"],
    "tf2_msgs/msg/TFMessage": ["transforms"],
    "neato2_interfaces/msg/Bump": ["left_front", "left_side", "right_front", "right_side"],
    "rosgraph_msgs/msg/Clock": ["clock"],
    # rcl_interfaces: parameters
    "rcl_interfaces/msg/ParameterType": [],
    "rcl_interfaces/msg/ParameterValue": [
        "type",
        "bool_value",
        "integer_value",
        "double_value",
        "string_value",
        "byte_array_value",
        "bool_array_value",
        "integer_array_value",
        "double_array_value",
        "string_array_value",
    ],
    "rcl_interfaces/msg/Parameter": ["name", "value"],
    "rcl_interfaces/msg/FloatingPointRange": ["from_value", "to_value", "step"],
    "rcl_interfaces/msg/IntegerRange": ["from_value", "to_value", "step"],
    "rcl_interfaces/msg/ParameterDescriptor": [
        "name",
        "type",
        "description",
        "additional_constraints",
        "read_only",
        "dynamic_typing",
        "floating_point_range",
        "integer_range",
    ],
    "rcl_interfaces/msg/SetParametersResult": ["successful", "reason"],
    "rcl_interfaces/msg/ListParametersResult": ["names", "prefixes"],
    "rcl_interfaces/msg/ParameterEvent": [
        "stamp",
        "node",
        "new_parameters",
        "changed_parameters",
        "deleted_parameters",
    ],
    "rcl_interfaces/srv/GetParameters_Request": ["names"],
    "rcl_interfaces/srv/GetParameters_Response": ["values"],
    "rcl_interfaces/srv/SetParameters_Request": ["parameters"],
    "rcl_interfaces/srv/SetParameters_Response": ["results"],
    "rcl_interfaces/srv/SetParametersAtomically_Request": ["parameters"],
    "rcl_interfaces/srv/SetParametersAtomically_Response": ["result"],
    "rcl_interfaces/srv/ListParameters_Request": ["prefixes", "depth"],
    "rcl_interfaces/srv/ListParameters_Response": ["result"],
    "rcl_interfaces/srv/DescribeParameters_Request": ["names"],
    "rcl_interfaces/srv/DescribeParameters_Response": ["descriptors"],
    "rcl_interfaces/srv/GetParameterTypes_Request": ["names"],
    "rcl_interfaces/srv/GetParameterTypes_Response": ["types"],
    "rosapi_msgs/msg/TypeDef": ["type", "fieldnames", "fieldtypes", "fieldarraylen", "examples", "constnames", "constvalues"],
    "rosapi_msgs/srv/ActionType_Request": ["action"],
    "rosapi_msgs/srv/ActionType_Response": ["type"],
    "rosapi_msgs/srv/DeleteParam_Request": ["name"],
    "rosapi_msgs/srv/DeleteParam_Response": ["successful", "reason"],
    "rosapi_msgs/srv/GetActionServers_Request": [],
    "rosapi_msgs/srv/GetActionServers_Response": ["action_servers"],
    "rosapi_msgs/srv/GetParamNames_Request": [],
    "rosapi_msgs/srv/GetParamNames_Response": ["names"],
    "rosapi_msgs/srv/GetParam_Request": ["name", "default_value"],
    "rosapi_msgs/srv/GetParam_Response": ["value", "successful", "reason"],
    "rosapi_msgs/srv/GetROSVersion_Request": [],
    "rosapi_msgs/srv/GetROSVersion_Response": ["version", "distro"],
    "rosapi_msgs/srv/GetTime_Request": [],
    "rosapi_msgs/srv/GetTime_Response": ["time"],
    "rosapi_msgs/srv/HasParam_Request": ["name"],
    "rosapi_msgs/srv/HasParam_Response": ["exists"],
    "rosapi_msgs/srv/Interfaces_Request": [],
    "rosapi_msgs/srv/Interfaces_Response": ["interfaces"],
    "rosapi_msgs/srv/MessageDetails_Request": ["type"],
    "rosapi_msgs/srv/MessageDetails_Response": ["typedefs"],
    "rosapi_msgs/srv/NodeDetails_Request": ["node"],
    "rosapi_msgs/srv/NodeDetails_Response": ["subscribing", "publishing", "services"],
    "rosapi_msgs/srv/Nodes_Request": [],
    "rosapi_msgs/srv/Nodes_Response": ["nodes"],
    "rosapi_msgs/srv/Publishers_Request": ["topic"],
    "rosapi_msgs/srv/Publishers_Response": ["publishers"],
    "rosapi_msgs/srv/SearchParam_Request": ["name"],
    "rosapi_msgs/srv/SearchParam_Response": ["global_name"],
    "rosapi_msgs/srv/ServiceHost_Request": ["service"],
    "rosapi_msgs/srv/ServiceHost_Response": ["host"],
    "rosapi_msgs/srv/ServiceNode_Request": ["service"],
    "rosapi_msgs/srv/ServiceNode_Response": ["node"],
    "rosapi_msgs/srv/ServiceProviders_Request": ["service"],
    "rosapi_msgs/srv/ServiceProviders_Response": ["providers"],
    "rosapi_msgs/srv/ServiceRequestDetails_Request": ["type"],
    "rosapi_msgs/srv/ServiceRequestDetails_Response": ["typedefs"],
    "rosapi_msgs/srv/ServiceResponseDetails_Request": ["type"],
    "rosapi_msgs/srv/ServiceResponseDetails_Response": ["typedefs"],
    "rosapi_msgs/srv/ServiceType_Request": ["service"],
    "rosapi_msgs/srv/ServiceType_Response": ["type"],
    "rosapi_msgs/srv/ServicesForType_Request": ["type"],
    "rosapi_msgs/srv/ServicesForType_Response": ["services"],
    "rosapi_msgs/srv/Services_Request": [],
    "rosapi_msgs/srv/Services_Response": ["services"],
    "rosapi_msgs/srv/SetParam_Request": ["name", "value"],
    "rosapi_msgs/srv/SetParam_Response": ["successful", "reason"],
    "rosapi_msgs/srv/Subscribers_Request": ["topic"],
    "rosapi_msgs/srv/Subscribers_Response": ["subscribers"],
    "rosapi_msgs/srv/TopicType_Request": ["topic"],
    "rosapi_msgs/srv/TopicType_Response": ["type"],
    "rosapi_msgs/srv/TopicsAndRawTypes_Request": [],
    "rosapi_msgs/srv/TopicsAndRawTypes_Response": ["topics", "types", "typedefs_full_text"],
    "rosapi_msgs/srv/TopicsForType_Request": ["type"],
    "rosapi_msgs/srv/TopicsForType_Response": ["topics"],
    "rosapi_msgs/srv/Topics_Request": [],
    "rosapi_msgs/srv/Topics_Response": ["topics", "types"],
}

# The types declared in Python; those of definition files are checked against their files in
# tests/shared_models/test_definition_packages.py.
MESSAGES = {
    name: cls
    for name, cls in all_interfaces().items()
    if issubclass(cls, Message) and not cls.__dict__.get("__ros_definition__")
}


def test_every_registered_message_has_its_ros_fields_listed_here() -> None:
    assert sorted(MESSAGES) == sorted(ROS_FIELDS)


@pytest.mark.parametrize("ros_type", sorted(MESSAGES))
def test_default_instance_round_trips_through_json_with_ros_keys(ros_type: str) -> None:
    cls = MESSAGES[ros_type]
    msg = cls()
    text = msg.model_dump_json()
    assert list(json.loads(text)) == ROS_FIELDS[ros_type]
    assert cls.model_validate_json(text) == msg
    assert cls.model_validate(msg.model_dump(mode="json")) == msg


def test_services_are_registered_with_their_parts() -> None:
    services = {
        name: cls
        for name, cls in all_interfaces().items()
        if issubclass(cls, ServiceType) and not cls.__dict__.get("__ros_definition__")
    }
    assert sorted(services) == [
        "rcl_interfaces/srv/DescribeParameters",
        "rcl_interfaces/srv/GetParameterTypes",
        "rcl_interfaces/srv/GetParameters",
        "rcl_interfaces/srv/ListParameters",
        "rcl_interfaces/srv/SetParameters",
        "rcl_interfaces/srv/SetParametersAtomically",
        "ros_workshop/srv/FlyCommand",
        "rosapi_msgs/srv/ActionType",
        "rosapi_msgs/srv/DeleteParam",
        "rosapi_msgs/srv/GetActionServers",
        "rosapi_msgs/srv/GetParam",
        "rosapi_msgs/srv/GetParamNames",
        "rosapi_msgs/srv/GetROSVersion",
        "rosapi_msgs/srv/GetTime",
        "rosapi_msgs/srv/HasParam",
        "rosapi_msgs/srv/Interfaces",
        "rosapi_msgs/srv/MessageDetails",
        "rosapi_msgs/srv/NodeDetails",
        "rosapi_msgs/srv/Nodes",
        "rosapi_msgs/srv/Publishers",
        "rosapi_msgs/srv/SearchParam",
        "rosapi_msgs/srv/ServiceHost",
        "rosapi_msgs/srv/ServiceNode",
        "rosapi_msgs/srv/ServiceProviders",
        "rosapi_msgs/srv/ServiceRequestDetails",
        "rosapi_msgs/srv/ServiceResponseDetails",
        "rosapi_msgs/srv/ServiceType",
        "rosapi_msgs/srv/Services",
        "rosapi_msgs/srv/ServicesForType",
        "rosapi_msgs/srv/SetParam",
        "rosapi_msgs/srv/Subscribers",
        "rosapi_msgs/srv/TopicType",
        "rosapi_msgs/srv/Topics",
        "rosapi_msgs/srv/TopicsAndRawTypes",
        "rosapi_msgs/srv/TopicsForType",
        "skydeck_launch/srv/KillNode",
        "skydeck_opencv/srv/WindowInput",
        "std_srvs/srv/Empty",
        "std_srvs/srv/SetBool",
        "std_srvs/srv/Trigger",
    ]
    for name, srv in services.items():
        assert srv.Request.__ros_type__ == name + "_Request"
        assert srv.Response.__ros_type__ == name + "_Response"


def test_model_class_names_are_unique_across_the_package() -> None:
    # OpenAPI component names come from class names.
    names = [cls.__name__ for cls in MESSAGES.values()]
    assert len(names) == len(set(names)), sorted(names)


def test_seed_usage_reads_like_ros() -> None:
    header = Header(stamp=Time(sec=12, nanosec=500), frame_id="odom")
    msg = PointStamped(header=header, point=Point(x=1.0, y=2.0, z=0.0))
    assert json.loads(msg.model_dump_json()) == {
        "header": {"seq": 0, "stamp": {"sec": 12, "nanosec": 500}, "frame_id": "odom"},
        "point": {"x": 1.0, "y": 2.0, "z": 0.0},
    }
    polygon = Polygon()
    polygon.points.append(Point32(x=1.0, y=2.0, z=0.0))
    assert Polygon().points == []  # the default list is not shared
    assert TriggerResponse(success=True, message="All ok!").message == "All ok!"
    assert isinstance(Trigger.Request(), TriggerRequest)
    assert Trigger.Response is TriggerResponse
    assert SetBool.Request(data=True).data is True
    assert FlyCommand.Request(x=1.5, y=-2.0).x == 1.5


def test_ros_defaults() -> None:
    assert Quaternion() == Quaternion(x=0.0, y=0.0, z=0.0, w=1.0)
    assert AiStatus().target == -1
    assert AiStatus().state == "idle"
    assert ControlState().state == "landed"
    assert State().mode == ""


def test_constants_are_class_attributes() -> None:
    assert (Log.DEBUG, Log.INFO, Log.WARN, Log.ERROR, Log.FATAL) == (10, 20, 30, 40, 50)
    assert PositionTarget.FRAME_LOCAL_NED == 1
    assert PositionTarget.FRAME_BODY_NED == 8
    assert PositionTarget.IGNORE_YAW_RATE == 2048
    assert "DEBUG" not in Log.model_fields
    assert "FRAME_LOCAL_NED" not in json.loads(PositionTarget().model_dump_json())


class TestCompressedImage:
    JPEG = bytes([0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0xFB, 0xFF, 0xD9])

    def test_raw_bytes_in_python_base64_in_json(self) -> None:
        image = CompressedImage(format="jpeg", data=self.JPEG)
        assert image.data == self.JPEG
        encoded = json.loads(image.model_dump_json())["data"]
        # The standard alphabet, so a browser can use it in a data: URL.
        assert encoded == base64.b64encode(self.JPEG).decode()
        assert CompressedImage.model_validate_json(image.model_dump_json()) == image

    def test_json_decoded_dict_and_int_list_are_accepted(self) -> None:
        image = CompressedImage(data=self.JPEG)
        assert CompressedImage.model_validate(image.model_dump(mode="json")).data == self.JPEG
        assert CompressedImage.model_validate({"data": list(self.JPEG)}).data == self.JPEG
        as_list = json.dumps({"data": list(self.JPEG)})
        assert CompressedImage.model_validate_json(as_list).data == self.JPEG
        url_safe = json.dumps({"data": base64.urlsafe_b64encode(self.JPEG).decode()})
        assert CompressedImage.model_validate_json(url_safe).data == self.JPEG

    def test_bad_data_is_refused(self) -> None:
        with pytest.raises(ValidationError, match="base64"):
            CompressedImage.model_validate({"data": "not base64!"})
        with pytest.raises(ValidationError, match="0 to 255"):
            CompressedImage.model_validate({"data": [1, 256]})


class TestValidation:
    @pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
    def test_non_finite_floats_are_refused_in_python(self, bad: float) -> None:
        with pytest.raises(ValidationError):
            Point(x=bad)
        with pytest.raises(ValidationError):
            PositionTarget(position=Point(z=bad))
        with pytest.raises(ValidationError):
            PositionTarget(yaw=bad)
        with pytest.raises(ValidationError):
            FlyCommand.Request(x=1.0, y=bad)

    @pytest.mark.parametrize("bad", ["NaN", "Infinity", "-Infinity"])
    def test_non_finite_floats_are_refused_in_json(self, bad: str) -> None:
        with pytest.raises(ValidationError):
            Point.model_validate_json(f'{{"x": {bad}, "y": 0, "z": 0}}')
        with pytest.raises(ValidationError):
            PositionTarget.model_validate_json(f'{{"position": {{"x": {bad}}}}}')
        with pytest.raises(ValidationError):
            FlyCommand.Request.model_validate_json(f'{{"x": {bad}, "y": 1.0}}')
        with pytest.raises(ValidationError):
            ControlState.model_validate_json(f'{{"setpoint": {{"y": {bad}}}}}')

    def test_unknown_field_is_refused(self) -> None:
        with pytest.raises(ValidationError, match="extra"):
            Point(x=1.0, w=2.0)  # type: ignore[call-arg]
        with pytest.raises(ValidationError, match="extra"):
            TriggerResponse.model_validate_json('{"success": true, "mesage": "typo"}')

    @pytest.mark.parametrize(
        ("cls", "field", "bad"),
        [
            (Header, "seq", -1),
            (Header, "seq", 2**32),
            (Time, "sec", 2**31),
            (Time, "nanosec", -1),
            (Log, "level", 256),
            (Log, "line", -1),
            (State, "system_status", 256),
            (PositionTarget, "coordinate_frame", -1),
            (PositionTarget, "type_mask", 0x10000),
            (AiStatus, "target", 2**31),
        ],
    )
    def test_int_ranges(self, cls: type[Message], field: str, bad: int) -> None:
        with pytest.raises(ValidationError):
            cls.model_validate({field: bad})

    def test_int_arrays_check_every_item(self) -> None:
        assert AiStatus(visited=[0, 3], tour=[2, 1]).tour == [2, 1]
        with pytest.raises(ValidationError):
            AiStatus(visited=[0, 2**31])

    def test_states_are_validated(self) -> None:
        for state in ("idle", "taking_off", "flying", "landing", "done", "error"):
            assert AiStatus.model_validate({"state": state}).state == state
        for state in ("landed", "taking_off", "flying", "landing"):
            assert ControlState.model_validate({"state": state}).state == state
        with pytest.raises(ValidationError):
            AiStatus.model_validate({"state": "landed"})
        with pytest.raises(ValidationError):
            ControlState.model_validate({"state": "done"})


def test_public_api_is_pinned() -> None:
    assert sorted(shared_models.__all__) == sorted(
        [
            "ActionType",
            "Message",
            "ServiceType",
            "all_interfaces",
            "get_interface",
            "interface_text",
            "interface_names",
            "UnknownInterfaceError",
            "resolve_name",
            "resolve_node_name",
            "InvalidNameError",
            "RESERVED_PREFIXES",
        ]
    )
    for name in shared_models.__all__:
        assert getattr(shared_models, name) is not None
