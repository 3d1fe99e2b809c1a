"""Definition files in ROS 1's syntax and ROS 2's become types that behave as the shipped ones:
fields, defaults, constants, bounds, nested types, services, actions; a malformed file is one
line naming file and line."""

from __future__ import annotations

import itertools
import json

import pytest
from pydantic import ValidationError

from shared_models import ActionType, Message, ServiceType, get_interface, interface_text
from shared_models.builtin_interfaces import Duration, Time
from shared_models.definitions.errors import DefinitionConflict, DefinitionError
from shared_models.definitions.loader import definitions_of, learn_definitions
from shared_models.definitions.parser import parse_definition
from shared_models.geometry_msgs import Point
from shared_models.std_msgs import Header

_packages = itertools.count()


def package() -> str:
    """A fresh package name per use: a process holds one version of each type."""
    return f"test_defs{next(_packages)}"


def learn(pkg: str, **files: str) -> None:
    """Learn ``Name_kind="text"`` files of ``pkg`` (``Status_msg``, ``Add_srv``, ``Fib_action``)."""
    learn_definitions({f"{pkg}/{key.rsplit('_', 1)[1]}/{key.rsplit('_', 1)[0]}": text for key, text in files.items()})


ROS2_MESSAGE = """# How a robot is doing
# (a header comment, as interface show prints it)

int32 MAX_SPEED=5
string NAME="fast # not a comment"
float64 PI = 3.14159

float64 speed 0.5          # m/s, a ROS 2 default
int32[] numbers [1, 2, 3]
int32[<=5] few
float32[3] fixed
string<=10 label "short"
string<=4[<=2] tags ["ab", 'cd']
bool flag true
uint8 small 255
int8 signed -128
char letter
byte raw
wstring wide
geometry_msgs/Point where
geometry_msgs/msg/Point[] path
Status status
"""


def test_ros2_syntax_fields_defaults_and_bounds() -> None:
    pkg = package()
    learn(pkg, Status_msg="uint8 OK=0\nuint8 level\n", Robot_msg=ROS2_MESSAGE)
    Robot = get_interface(f"{pkg}/msg/Robot")
    robot = Robot()
    assert robot.model_dump(mode="json") == {
        "speed": 0.5, "numbers": [1, 2, 3], "few": [], "fixed": [0.0, 0.0, 0.0], "label": "short",
        "tags": ["ab", "cd"], "flag": True, "small": 255, "signed": -128, "letter": 0, "raw": 0, "wide": "",
        "where": {"x": 0.0, "y": 0.0, "z": 0.0}, "path": [], "status": {"level": 0},
    }  # fmt: skip
    assert (Robot.MAX_SPEED, Robot.NAME, Robot.PI) == (5, "fast # not a comment", 3.14159)
    assert "MAX_SPEED" not in Robot.model_fields  # constants are ClassVars, never fields
    assert isinstance(robot.where, Point) and type(robot.status) is get_interface(f"{pkg}/msg/Status")
    for bad in ({"few": [1] * 6}, {"fixed": [1.0, 2.0]}, {"label": "x" * 11}, {"tags": ["abcde"]},
                {"small": 256}, {"signed": -129}, {"speed": "fast"}, {"flag": 1}, {"unknown": 1}):  # fmt: skip
        with pytest.raises(ValidationError):
            Robot.model_validate(bad)
    with pytest.raises(ValidationError):
        robot.speed = float("nan")  # assignments are validated, as a hand-written type's


def test_interface_show_prints_it_as_ros_does() -> None:
    pkg = package()
    learn(pkg, Status_msg="uint8 level\n", Robot_msg=ROS2_MESSAGE)
    text = interface_text(f"{pkg}/msg/Robot")
    assert text.startswith(
        "# How a robot is doing\n# (a header comment, as interface show prints it)\n\n"
        'int32 MAX_SPEED=5\nstring NAME=fast # not a comment\nfloat64 PI=3.14159\n\n'
        "float64 speed 0.5\nint32[] numbers [1, 2, 3]\nint32[<=5] few\nfloat32[3] fixed\n"
        'string<=10 label "short"\nstring<=4[<=2] tags ["ab", "cd"]\nbool flag true\nuint8 small 255\n'
        "int8 signed -128\nchar letter\nbyte raw\nwstring wide\n"
        "geometry_msgs/Point where\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\ngeometry_msgs/Point[] path\n"
    )
    assert text.endswith("Status status\n\tuint8 level")


ROS1_MESSAGE = """Header header
time stamp
duration timeout
string SHOUT=Hello there # everything after = is the value in ROS 1
int32 X = 5
uint8 MODE_A=1
geometry_msgs/Point32[4] corners
"""


def test_ros1_syntax_aliases_and_positional_construction() -> None:
    pkg = package()
    learn(pkg, Old_msg=ROS1_MESSAGE)
    Old = get_interface(f"{pkg}/Old")  # ROS 1's spelling of the name
    assert Old.SHOUT == "Hello there # everything after = is the value in ROS 1" and Old.X == 5
    old = Old(Header(frame_id="map"), Time(3, 5), Duration(1.5))  # genpy's positional form
    assert (old.header.frame_id, old.stamp.nanosec, old.timeout.to_sec()) == ("map", 5, 1.5)
    assert len(old.corners) == 4
    assert [name for name, _ in Old.model_fields.items()] == ["header", "stamp", "timeout", "corners"]
    with pytest.raises(TypeError, match="at most 4 positional"):
        Old(1, 2, 3, 4, 5)


def test_json_round_trip_is_the_shipped_types_json() -> None:
    pkg = package()
    learn(pkg, Blob_msg="uint8[] data\nuint8[4] fixed\nbyte[] more\n")
    Blob = get_interface(f"{pkg}/msg/Blob")
    blob = Blob(data=b"\x01\x02", fixed=[1, 2, 3, 4])
    text = blob.model_dump_json()
    assert json.loads(text) == {"data": "AQI=", "fixed": "AQIDBA==", "more": ""}  # base64, as sensor_msgs/Image's
    assert Blob.model_validate_json(text) == blob
    with pytest.raises(ValidationError):
        Blob(fixed=b"\x00")


def test_service_parts_have_ros1_and_ros2_names() -> None:
    pkg = package()
    learn(pkg, AddTwoInts_srv="# add them\nint64 a\nint64 b\n---\nint64 sum\n")
    srv = get_interface(f"{pkg}/srv/AddTwoInts")
    assert issubclass(srv, ServiceType) and srv.Request is get_interface(f"{pkg}/srv/AddTwoInts_Request")
    assert srv.Request.__name__ == "AddTwoIntsRequest" and srv.Response(sum=3).sum == 3
    assert interface_text(srv) == "# add them\n\nint64 a\nint64 b\n---\nint64 sum"


def test_an_action_and_everything_derived_from_it() -> None:
    pkg = package()
    learn(pkg, Count_action="int32 target\n---\nint32[] counted\n---\nint32 so_far\n")
    action = get_interface(f"{pkg}/action/Count")
    assert issubclass(action, ActionType)
    assert action.Goal(target=3).target == 3 and action.Feedback.__ros_type__ == f"{pkg}/action/Count_Feedback"
    send = action.Impl.SendGoalService
    assert send is action.SendGoal and send.__ros_type__ == f"{pkg}/action/Count_SendGoal"
    assert list(send.Request.model_fields) == ["goal_id", "goal"] and list(send.Response.model_fields) == ["accepted", "stamp"]
    assert list(action.GetResult.Response.model_fields) == ["status", "result"]
    assert list(action.FeedbackMessage.model_fields) == ["goal_id", "feedback"]
    assert action.Impl.CancelGoalService is get_interface("action_msgs/srv/CancelGoal")
    assert action.Impl.GoalStatusMessage is get_interface("action_msgs/msg/GoalStatusArray")
    ros1 = {name: get_interface(f"{pkg}/msg/Count{name}") for name in ("Goal", "ActionGoal", "ActionResult", "ActionFeedback", "Action")}
    assert list(ros1["ActionGoal"].model_fields) == ["header", "goal_id", "goal"]
    assert list(ros1["ActionResult"].model_fields) == ["header", "status", "result"]
    assert list(ros1["Action"].model_fields) == ["action_goal", "action_result", "action_feedback"]
    assert ros1["ActionGoal"]().goal_id.id == "" and ros1["Goal"](7).target == 7
    assert interface_text(action) == "int32 target\n---\nint32[] counted\n---\nint32 so_far"


def test_a_type_of_the_same_package_may_come_later_in_the_list() -> None:
    pkg = package()
    learn(pkg, Outer_msg="Inner inner\nInner[] many\n", Inner_msg="float32 v 1.5\n")
    assert get_interface(f"{pkg}/msg/Outer")().inner.v == 1.5


def test_definitions_of_a_type_are_what_another_process_needs() -> None:
    pkg = package()
    learn(pkg, Inner_msg="float32 v\n", Outer_msg="Inner inner\ngeometry_msgs/Point p\n")
    outer = get_interface(f"{pkg}/msg/Outer")
    assert definitions_of([outer]) == {f"{pkg}/msg/Outer": "Inner inner\ngeometry_msgs/Point p\n", f"{pkg}/msg/Inner": "float32 v\n"}
    assert definitions_of([Point, get_interface("example_interfaces/srv/AddTwoInts")]) == {}  # shipped ones


def test_the_same_definition_again_is_nothing_and_another_is_a_conflict() -> None:
    pkg = package()
    learn(pkg, Status_msg="# first\nint32 level\n")
    learn(pkg, Status_msg="# a new comment changes nothing\nint32 level\n")
    with pytest.raises(DefinitionConflict, match=rf"{pkg}/msg/Status \(from node /talker\) differs from the definition"):
        learn_definitions({f"{pkg}/msg/Status": "int64 level\n"}, source="node /talker")
    with pytest.raises(DefinitionConflict, match="a type Skydeck declares itself"):
        learn_definitions({"geometry_msgs/msg/Point": "float64 x\n"})


def test_generated_classes_are_messages_like_the_shipped_ones() -> None:
    pkg = package()
    learn(pkg, Plain_msg="float64 x\n")
    plain = get_interface(f"{pkg}/msg/Plain")
    assert issubclass(plain, Message) and type(plain) is type(Point)  # one type system, one metaclass
    assert repr(plain(x=1.0)) == f"{pkg}.msg.Plain(x=1.0)"


@pytest.mark.parametrize(
    ("text", "kind", "line", "problem"),
    [
        ("int32 a\nflaot64 b\n", "msg", 2, "unknown type 'flaot64' (did you mean float64? "),
        ("int32\n", "msg", 1, "expected `TYPE NAME`"),
        ("int32 a\nint32 a\n", "msg", 2, "'a' is declared twice"),
        ("int32 a 1.5\n", "msg", 1, "field a: '1.5' is not an integer"),
        ("uint8 a 256\n", "msg", 1, "field a: 256 is out of range for uint8 (0 to 255)"),
        ("bool a maybe\n", "msg", 1, "field a: 'maybe' is not a bool"),
        ("float64 X=nan\n", "msg", 1, "constant X: 'nan' is not finite"),
        ("int32 X=\n", "msg", 1, "constant X has no value"),
        ("geometry_msgs/Point X=1\n", "msg", 1, "constant X must have a primitive type"),
        ("geometry_msgs/Point p 1\n", "msg", 1, "field p: only primitive fields and arrays of them take a default"),
        ("int32[3] a [1, 2]\n", "msg", 1, "field a: 2 values for a fixed array of 3"),
        ("int32[<=1] a [1, 2]\n", "msg", 1, "field a: 2 values for at most 1"),
        ("int32[] a 5\n", "msg", 1, "field a: an array's default is a list, e.g. [1, 2, 3]; got '5'"),
        ("int32[] a [1, 2\n", "msg", 1, "field a: the list '[1, 2' has no closing ]"),
        ('string s "open\n', "msg", 1, "unterminated string"),
        ("string<=2 s 'abc'\n", "msg", 1, "field s: 'abc' is longer than 2 characters"),
        ("int32<=3 a\n", "msg", 1, "only string and wstring take a bound"),
        ("int32[<=] a\n", "msg", 1, "'int32[<=]': a bounded array needs its bound"),
        ("int32 json\n", "msg", 1, "'json' cannot be a field or constant name in Skydeck"),
        ("int32 a\n", "srv", None, "a .srv file has one `---` line (request, then response); this one has 0"),
        ("int32 a\n---\n", "action", None, "a .action file has two `---` lines (goal, result, feedback); this one has 1"),
        ("Missing m\n", "msg", 1, "unknown type 'Missing': there is no {pkg}/msg/Missing.msg"),
        ("geometry_msgs/Pointt p\n", "msg", 1, "unknown type 'geometry_msgs/Pointt': geometry_msgs has no msg Pointt (it has: Accel"),
        ("nope_msgs/Thing t\n", "msg", 1, "unknown type 'nope_msgs/Thing': no package nope_msgs is known"),
        ("Bad b\n", "msg", None, "{pkg}/msg/Bad contains itself ({pkg}/msg/Bad -> {pkg}/msg/Bad)"),
    ],
)
def test_a_malformed_file_is_one_line_naming_file_and_line(text: str, kind: str, line: int | None, problem: str) -> None:
    pkg = package()
    with pytest.raises(DefinitionError) as raised:
        learn_definitions({f"{pkg}/{kind}/Bad": text})
    message = str(raised.value)
    where = f"{pkg}/{kind}/Bad" + (f":{line}" if line else "")
    assert message.startswith(f"{where}: {problem.format(pkg=pkg)}"), message
    assert "\n" not in message


def test_the_file_name_is_in_the_error_when_read_from_a_package() -> None:
    with pytest.raises(DefinitionError, match=r"^my_pkg/msg/Bad.msg:3: unknown type 'flaot64'"):
        parse_definition("# comment\nint32 a\nflaot64 b\n", "my_pkg/msg/Bad", origin="my_pkg/msg/Bad.msg")


def test_a_definition_that_fails_half_way_leaves_nothing_and_builds_once_fixed() -> None:
    pkg = package()
    with pytest.raises(DefinitionError, match="'json' cannot be a field"):
        learn(pkg, Move_action="int32 goal\n---\nint32 result\n---\nint32 json\n")  # goal and result built first
    learn(pkg, Move_action="int32 goal\n---\nint32 result\n---\nint32 feedback\n")
    assert get_interface(f"{pkg}/action/Move").Feedback(feedback=2).feedback == 2
