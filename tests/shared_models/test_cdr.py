"""The CDR codec and the ros2msg definitions, against bytes worked out by hand from the rules
(the interop with ROS 2's own serialiser is tests/services/protocols/ros2/test_types.py)."""

from __future__ import annotations

import struct

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shared_models import all_interfaces, get_interface
from shared_models._message import Message
from shared_models.cdr import CdrError, codec_for, codec_of
from shared_models.definitions.errors import DefinitionError
from shared_models.ros2msg import (
    definition_text,
    message_spec,
    msg_file_text,
    parse_definition,
    specs_of,
    srv_file_text,
)

pytestmark = pytest.mark.timeout(60)

HEADER = b"\x00\x01\x00\x00"


def test_a_string_counts_its_nul_and_a_point_aligns_its_doubles_after_the_header() -> None:
    assert codec_of(get_interface("std_msgs/msg/String")).encode({"data": "hi"}) == HEADER + b"\x03\x00\x00\x00hi\x00"
    point = codec_of(get_interface("geometry_msgs/msg/Point")).encode({"x": 1.0, "y": 2.0, "z": -1.0})
    assert point == HEADER + struct.pack("<3d", 1.0, 2.0, -1.0)


def test_alignment_counts_from_the_end_of_the_encapsulation_header() -> None:
    # Header: int32 sec, uint32 nanosec, string "odom"; then a float64 that must sit at payload
    # offset 24 (17 bytes used, padded to 8), i.e. byte 28 of the whole buffer.
    stamped = codec_of(get_interface("geometry_msgs/msg/Vector3Stamped"))
    data = stamped.encode({"header": {"stamp": {"sec": 7, "nanosec": 9}, "frame_id": "odom"}, "vector": {"x": 0.5}})
    payload = data[4:]
    assert payload[:8] == struct.pack("<iI", 7, 9)
    assert payload[8:17] == struct.pack("<I", 5) + b"odom\x00"
    assert payload[17:24] == bytes(7)
    assert struct.unpack_from("<3d", payload, 24) == (0.5, 0.0, 0.0)
    assert stamped.decode(data) == {
        "header": {"stamp": {"sec": 7, "nanosec": 9}, "frame_id": "odom"},
        "vector": {"x": 0.5, "y": 0.0, "z": 0.0},
    }


def test_sequences_fixed_arrays_bytes_and_empty_messages() -> None:
    image = codec_of(get_interface("sensor_msgs/msg/CompressedImage"))
    data = image.encode({"header": {}, "format": "jpeg", "data": b"\xff\xd8"})
    assert data.endswith(struct.pack("<I", 2) + b"\xff\xd8")
    assert image.decode(data)["data"] == b"\xff\xd8"
    # base64 text (a JSON frame's) and a list of ints are the same bytes
    assert image.encode({"format": "jpeg", "data": "/9g="}) == image.encode({"format": "jpeg", "data": [255, 216]})
    empty = codec_of(get_interface("std_msgs/msg/Empty"))
    assert empty.encode({}) == HEADER + b"\x00"
    assert empty.decode(HEADER + b"\x00\x00\x00\x00") == {}
    covariance = codec_of(get_interface("geometry_msgs/msg/PoseWithCovariance"))
    with pytest.raises(CdrError, match="covariance must have 36 items, not 2"):
        covariance.encode({"covariance": [0.0, 1.0]})
    descriptor = codec_of(get_interface("rcl_interfaces/msg/ParameterDescriptor"))
    with pytest.raises(CdrError, match="at most 1 items"):
        descriptor.encode({"integer_range": [{}, {}]})


def test_a_missing_field_is_its_zero_and_header_seq_stays_home() -> None:
    header = codec_of(get_interface("std_msgs/msg/Header"))
    assert header.encode({"seq": 41, "frame_id": "map"}) == header.encode({"frame_id": "map"})
    assert "seq" not in header.decode(header.encode({"seq": 41}))
    assert [f.name for f in message_spec(get_interface("std_msgs/msg/Header")).fields] == ["stamp", "frame_id"]


def test_bad_values_and_bad_bytes_are_one_error_naming_the_type() -> None:
    point = codec_of(get_interface("geometry_msgs/msg/Point"))
    with pytest.raises(CdrError, match="geometry_msgs/msg/Point: cannot encode"):
        point.encode({"x": "one"})
    with pytest.raises(CdrError, match="geometry_msgs/msg/Point: 12 bytes are not one message"):
        point.decode(HEADER + bytes(8))
    with pytest.raises(CdrError, match="not little-endian plain CDR"):
        point.decode(b"\x00\x00\x00\x00" + bytes(24))
    text = codec_of(get_interface("std_msgs/msg/String"))
    with pytest.raises(CdrError, match="not one message"):
        text.decode(HEADER + struct.pack("<I", 100) + b"abc")


def test_the_definition_text_is_the_msg_file_then_each_dependency() -> None:
    text = definition_text(get_interface("geometry_msgs/msg/PoseStamped"))
    assert text.startswith("std_msgs/Header header\nPose pose\n" + "=" * 80 + "\nMSG: std_msgs/Header\n")
    assert "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w 1\n" in text
    assert text.count("MSG: builtin_interfaces/Time") == 1
    marker = msg_file_text(get_interface("visualization_msgs/msg/Marker"))
    assert marker.startswith("int32 ARROW=0\n") and "UVCoordinate[] uv_coordinates\n" in marker
    assert srv_file_text(get_interface("ros_workshop/srv/FlyCommand")) == (
        "float32 x\nfloat32 y\n---\nbool success\nstring message\n"
    )


@pytest.mark.parametrize("name", sorted(n for n, c in all_interfaces().items() if issubclass(c, Message)))
def test_every_definition_reads_back_as_the_same_specs(name: str) -> None:
    cls = get_interface(name)
    specs = specs_of(cls)
    parsed = parse_definition(name, definition_text(cls))
    assert parsed == specs
    codec = codec_of(cls)
    assert cls.model_validate(codec.decode(codec.encode(cls().model_dump()))) == cls()


def test_a_definition_from_elsewhere_reads_with_comments_constants_and_ros1_spellings() -> None:
    text = (
        "# a reading\nuint8 KIND_A=1  # the first kind\nstring LABEL = \"a # not a comment\"\n"
        "Header header\nfloat64[<=3] values # up to three\nstring<=8 name\nDetail[2] details\n"
        + "=" * 80 + "\nMSG: demo_msgs/Detail\ntime at\nbyte[] raw\n"
    )
    with pytest.raises(DefinitionError, match="std_msgs/msg/Header, which the definition does not include"):
        parse_definition("demo_msgs/Reading", text)
    text += "=" * 80 + "\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
    specs = parse_definition("demo_msgs/Reading", text)
    reading = specs["demo_msgs/msg/Reading"]
    assert reading.constants == (("uint8", "KIND_A", "1"), ("string", "LABEL", '"a # not a comment"'))
    assert [(f.name, f.type, f.array, f.bounded) for f in reading.fields] == [
        ("header", "std_msgs/msg/Header", None, False),
        ("values", "float64", 3, True),
        ("name", "string", None, False),
        ("details", "demo_msgs/msg/Detail", 2, False),
    ]
    codec = codec_for("demo_msgs/msg/Reading", specs)
    value = {
        "header": {"seq": 3, "stamp": {"sec": 1, "nanosec": 2}, "frame_id": "f"},
        "values": [1.5], "name": "n", "details": [{"at": {"sec": 0, "nanosec": 0}, "raw": b"\x01"}] * 2,
    }
    assert codec.decode(codec.encode(value)) == value
    with pytest.raises(DefinitionError, match="demo_msgs/msg/Bad:1: cannot read 'float64'"):
        parse_definition("demo_msgs/Bad", "float64\n")


@settings(max_examples=60, deadline=None)
@given(
    st.floats(allow_nan=False, allow_infinity=False, width=32),
    st.lists(st.floats(allow_nan=False, allow_infinity=False, width=32), max_size=20),
    st.text(alphabet=st.characters(blacklist_categories=("Cs",), blacklist_characters="\x00"), max_size=30),
    st.integers(-(2**31), 2**31 - 1),
    st.integers(0, 999_999_999),
)
def test_a_laser_scan_round_trips_through_cdr(
    angle: float, ranges: list[float], frame: str, sec: int, nanosec: int
) -> None:
    cls = get_interface("sensor_msgs/msg/LaserScan")
    message = cls(header={"stamp": {"sec": sec, "nanosec": nanosec}, "frame_id": frame}, angle_min=angle, ranges=ranges)
    codec = codec_of(cls)
    back = cls.model_validate(codec.decode(codec.encode(message.model_dump())))
    assert back == message
