"""The ROS module names: message views that ARE the shared_models types, the façade aliases, and
one clear line for an unknown package, an unknown type or a ROS API Skydeck does not provide."""

from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

import pytest

from services.ros import disable_ros_imports, enable_ros_imports
from services.ros.errors import (
    NotProvidedImportError,
    UnknownMessageError,
    UnknownMessagePackageError,
)
from shared_models import geometry_msgs, rcl_interfaces, ros_workshop, sensor_msgs, std_srvs

pytestmark = pytest.mark.usefixtures("ros_imports")

REPO = Path(__file__).resolve().parents[2]


def test_message_views_are_the_shared_models_classes() -> None:
    from geometry_msgs.msg import Point, PointStamped, Twist
    from sensor_msgs.msg import CompressedImage, Image, Imu, LaserScan

    assert Twist is geometry_msgs.Twist and Point is geometry_msgs.Point and PointStamped is geometry_msgs.PointStamped
    assert (LaserScan, Image, CompressedImage, Imu) == (
        sensor_msgs.LaserScan, sensor_msgs.Image, sensor_msgs.CompressedImage, sensor_msgs.Imu,
    )  # fmt: skip
    msg = Twist()
    msg.linear.x = 0.1
    assert msg.model_dump_json() == geometry_msgs.Twist(linear=geometry_msgs.Vector3(x=0.1)).model_dump_json()


@pytest.mark.parametrize(
    ("module", "names"),
    [
        ("std_msgs.msg", ["Header", "String", "Bool", "Int32", "Float64", "Empty", "ColorRGBA"]),
        ("geometry_msgs.msg", ["Pose", "Quaternion", "PoseArray", "Polygon", "TransformStamped"]),
        ("nav_msgs.msg", ["Odometry", "Path"]),
        ("visualization_msgs.msg", ["Marker", "MarkerArray"]),
        ("tf2_msgs.msg", ["TFMessage"]),
        ("builtin_interfaces.msg", ["Time", "Duration"]),
        ("rcl_interfaces.msg", ["SetParametersResult", "ParameterDescriptor", "Log"]),
        ("mavros_msgs.msg", ["State", "PositionTarget"]),
        ("neato2_interfaces.msg", ["Bump"]),
        ("std_srvs.srv", ["Trigger", "TriggerRequest", "TriggerResponse", "Empty", "EmptyRequest", "SetBool"]),
        ("ros_workshop.srv", ["FlyCommand", "FlyCommandRequest", "FlyCommandResponse"]),
        ("rcl_interfaces.srv", ["GetParameters", "SetParameters"]),
    ],
)
def test_the_issues_types_import_under_ros_names(module: str, names: list[str]) -> None:
    view = importlib.import_module(module)
    for name in names:
        assert getattr(view, name).__ros_type__.startswith(module.replace(".", "/").split("/")[0] + "/")


def test_ros1_and_ros2_service_spellings_are_one_class() -> None:
    from ros_workshop.srv import FlyCommand, FlyCommandRequest, FlyCommandResponse
    from std_srvs.srv import Trigger, Trigger_Request, TriggerRequest, TriggerResponse

    assert Trigger.Request is TriggerRequest is Trigger_Request is std_srvs.TriggerRequest
    assert Trigger.Response is TriggerResponse
    assert FlyCommand.Request is FlyCommandRequest is ros_workshop.FlyCommandRequest
    assert FlyCommandResponse(True, "ok").success is True  # ROS 1's positional form


def test_a_view_holds_only_its_own_kind() -> None:
    rcl_msg = importlib.import_module("rcl_interfaces.msg")
    workshop_msg = importlib.import_module("ros_workshop.msg")

    assert rcl_msg.Log is rcl_interfaces.Log and not hasattr(rcl_msg, "GetParameters")
    assert not hasattr(workshop_msg, "FlyCommand")  # a service, in .srv
    assert "SimWorld" in workshop_msg.__all__


def test_package_then_submodule_attribute_access() -> None:
    import geometry_msgs as package

    importlib.import_module("geometry_msgs.msg")
    assert package.msg.Point is geometry_msgs.Point


def test_unknown_package_is_one_line_naming_the_known_ones() -> None:
    with pytest.raises(UnknownMessagePackageError) as raised:
        importlib.import_module("foo_msgs.msg")
    text = str(raised.value)
    assert text.startswith("`foo_msgs` is not a message package Skydeck knows; known: builtin_interfaces, std_msgs")
    assert "\n" not in text and isinstance(raised.value, ImportError)


def test_unknown_type_in_a_known_package() -> None:
    with pytest.raises(UnknownMessageError, match="`std_msgs.msg` has no type 'Foo' in Skydeck; it has: Bool"):
        exec("from std_msgs.msg import Foo", {})
    view = importlib.import_module("std_msgs.msg")
    assert not hasattr(view, "lowercase_probe")  # probes of other names stay AttributeErrors


@pytest.mark.parametrize(
    ("module", "message"),
    [
        ("rclpy.lifecycle", "`rclpy.lifecycle` is a ROS API Skydeck does not provide (yet)"),
        ("message_filters", "`message_filters` is a ROS API Skydeck does not provide"),
    ],
)
def test_apis_not_provided_name_themselves(module: str, message: str) -> None:
    with pytest.raises(NotProvidedImportError, match=message.replace("(", r"\(").replace(")", r"\)")):
        importlib.import_module(module)


def test_services_of_a_package_without_any() -> None:
    with pytest.raises(UnknownMessageError, match="`geometry_msgs` has no services"):
        importlib.import_module("geometry_msgs.srv")


def test_rclpy_is_the_facade_module_itself() -> None:
    import rclpy
    import rclpy.node

    from services.ros import rclpy as facade

    assert rclpy is facade and rclpy.node is sys.modules["services.ros.rclpy.node"]
    assert rclpy.__spec__.name == "services.ros.rclpy"  # it keeps its own identity


def test_other_modules_are_left_to_python() -> None:
    assert importlib.import_module("json").__name__ == "json"
    with pytest.raises(ModuleNotFoundError, match="No module named 'not_a_ros_thing'"):
        importlib.import_module("not_a_ros_thing")


def test_nothing_is_importable_without_the_finder() -> None:
    from shared_models.geometry_msgs import Twist

    disable_ros_imports()
    before = set(sys.modules)
    try:
        module = importlib.import_module("geometry_msgs.msg")
    except ModuleNotFoundError:
        pass
    else:  # a real ROS 2 is installed (the ros2 extra): its own package, never Skydeck's view
        assert module.Twist is not Twist
    finally:
        for name in set(sys.modules) - before:
            if name.split(".")[0] in {"geometry_msgs", "builtin_interfaces", "std_msgs", "rosidl_parser", "rpyutils"}:
                del sys.modules[name]
        enable_ros_imports()


def _skydeck_run(tmp_path: Path, source: str) -> subprocess.CompletedProcess[str]:
    path = tmp_path / "node.py"
    path.write_text(source)
    return subprocess.run(
        [sys.executable, "-m", "services.cli", "run", str(path)],
        cwd=REPO, capture_output=True, text=True, timeout=60,
    )  # fmt: skip


@pytest.mark.parametrize(
    ("source", "line"),
    [
        ("import foo_msgs.msg\n", "skydeck: error: `foo_msgs` is not a message package Skydeck knows; known: "),
        ("from rclpy.lifecycle import LifecycleNode\n", "skydeck: error: `rclpy.lifecycle` is a ROS API Skydeck does not provide"),
        ("def main():\n    from std_msgs.msg import Strin\n\nif __name__ == '__main__':\n    main()\n",
         "skydeck: error: `std_msgs.msg` has no type 'Strin' in Skydeck"),
    ],
)  # fmt: skip
def test_skydeck_run_prints_one_line_and_exits_1(tmp_path: Path, source: str, line: str) -> None:
    result = _skydeck_run(tmp_path, source)
    assert result.returncode == 1
    assert result.stderr.startswith(line) and result.stderr.count("\n") == 1, result.stderr
    assert "Traceback" not in result.stderr


def test_skydeck_run_imports_messages_for_a_plain_script(tmp_path: Path) -> None:
    result = _skydeck_run(
        tmp_path,
        "from geometry_msgs.msg import Pose, Point, Quaternion\n"
        "print(Pose(Point(1, 2, 3), Quaternion(0, 0, 0, 1)).position.y)\n",
    )
    assert result.returncode == 0 and result.stdout == "2.0\n", result.stderr


def test_a_package_without_actions_says_so() -> None:
    with pytest.raises(UnknownMessageError, match=r"`geometry_msgs` has no actions in Skydeck \(no `geometry_msgs.action`\)"):
        importlib.import_module("geometry_msgs.action")
