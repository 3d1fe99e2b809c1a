"""The tutorials' interfaces Skydeck ships as definition files import under ROS 1's and ROS 2's
names, with the fields the tutorials use, as a course's code imports them."""

from __future__ import annotations

import importlib

import pytest

from services.ros import disable_ros_imports, enable_ros_imports
from services.ros.errors import NotProvidedError
from shared_models import ActionType, Message, ServiceType

pytestmark = pytest.mark.usefixtures("ros_imports")


def fields(cls: type[Message]) -> list[str]:
    return list(cls.model_fields)


def test_ros2_tutorials_add_two_ints_and_fibonacci() -> None:
    from example_interfaces.action import Fibonacci
    from example_interfaces.msg import Int64, String
    from example_interfaces.srv import AddTwoInts, SetBool, Trigger

    request = AddTwoInts.Request()
    request.a, request.b = 41, 1
    assert AddTwoInts.Response(sum=request.a + request.b).sum == 42
    assert issubclass(Fibonacci, ActionType) and fields(Fibonacci.Goal) == ["order"]
    assert fields(Fibonacci.Result) == ["sequence"] and fields(Fibonacci.Feedback) == ["sequence"]
    feedback = Fibonacci.Feedback()
    feedback.sequence = [0, 1]
    feedback.sequence.append(feedback.sequence[-1] + feedback.sequence[-2])
    assert Fibonacci.Feedback.model_validate(feedback.model_dump()).sequence == [0, 1, 1]
    assert String(data="hi").data == "hi" and Int64(data=2**40).data == 2**40
    assert fields(SetBool.Request) == ["data"] and fields(Trigger.Response) == ["success", "message"]


def test_ros1_tutorials_add_two_ints_with_rospy_names() -> None:
    from rospy_tutorials.msg import Floats, HeaderString
    from rospy_tutorials.srv import AddTwoInts, AddTwoIntsRequest, AddTwoIntsResponse

    assert AddTwoInts.Request is AddTwoIntsRequest and AddTwoInts.Response is AddTwoIntsResponse
    assert AddTwoIntsRequest(1, 2).b == 2 and AddTwoIntsResponse(3).sum == 3  # genpy's positional form
    assert Floats(data=[1.5]).data == [1.5] and fields(HeaderString) == ["header", "data"]


def test_turtlesim() -> None:
    from turtlesim.action import RotateAbsolute
    from turtlesim.msg import Color, Pose
    from turtlesim.srv import Kill, SetPen, Spawn, SpawnRequest, TeleportAbsolute, TeleportRelative

    assert fields(Pose) == ["x", "y", "theta", "linear_velocity", "angular_velocity"]
    assert fields(Color) == ["r", "g", "b"]
    assert fields(Spawn.Request) == ["x", "y", "theta", "name"] and fields(Spawn.Response) == ["name"]
    assert SpawnRequest is Spawn.Request and fields(Kill.Request) == ["name"] and fields(Kill.Response) == []
    assert fields(SetPen.Request) == ["r", "g", "b", "width", "off"]
    assert fields(TeleportAbsolute.Request) == ["x", "y", "theta"]
    assert fields(TeleportRelative.Request) == ["linear", "angular"]
    assert fields(RotateAbsolute.Goal) == ["theta"] and fields(RotateAbsolute.Result) == ["delta"]
    assert fields(RotateAbsolute.Feedback) == ["remaining"]


def test_actionlib_tutorials_as_ros1_imports_them() -> None:
    import actionlib_tutorials.msg
    from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray

    msgs = actionlib_tutorials.msg
    goal = msgs.FibonacciGoal(order=20)
    action_goal = msgs.FibonacciActionGoal(goal=goal, goal_id=GoalID(id="g1"))
    assert action_goal.goal.order == 20 and fields(msgs.FibonacciActionGoal) == ["header", "goal_id", "goal"]
    assert fields(msgs.FibonacciActionResult) == ["header", "status", "result"]
    assert fields(msgs.FibonacciActionFeedback) == ["header", "status", "feedback"]
    assert fields(msgs.FibonacciAction) == ["action_goal", "action_result", "action_feedback"]
    assert fields(msgs.AveragingGoal) == ["samples"] and fields(msgs.AveragingResult) == ["mean", "std_dev"]
    assert fields(msgs.AveragingFeedback) == ["sample", "data", "mean", "std_dev"]
    assert (GoalStatus.PENDING, GoalStatus.SUCCEEDED, GoalStatus.LOST) == (0, 3, 9)
    assert fields(GoalStatus) == ["goal_id", "status", "text"] and fields(GoalStatusArray) == ["header", "status_list"]


def test_actionlib_test_actions_beside_its_api() -> None:
    import actionlib
    from actionlib.msg import TestAction, TestGoal, TestRequestGoal, TwoIntsGoal, TwoIntsResult

    assert fields(TestGoal) == ["goal"] and TestAction().action_goal.goal.goal == 0
    assert TestRequestGoal.TERMINATE_EXCEPTION == 5 and TestRequestGoal().delay_accept.to_sec() == 0.0
    assert TwoIntsResult(sum=TwoIntsGoal(a=1, b=2).b + 1).sum == 3
    from actionlib import SimpleActionClient, SimpleActionServer

    assert SimpleActionServer.__module__ == "services.ros.actionlib.simple_action_server" and SimpleActionClient
    assert actionlib.GoalStatus.SUCCEEDED == 3 and actionlib.get_name_of_constant(actionlib.GoalStatus, 2) == "PREEMPTED"
    with pytest.raises(NotProvidedError, match=r"`actionlib.ActionClient` \(use SimpleActionClient\) is a ROS API Skydeck does not provide"):
        exec("from actionlib import ActionClient", {})


def test_ros2_action_types_under_rclpy_names() -> None:
    from action_msgs.msg import GoalInfo, GoalStatus, GoalStatusArray
    from action_msgs.srv import CancelGoal
    from example_interfaces.action import Fibonacci
    from unique_identifier_msgs.msg import UUID

    impl = Fibonacci.Impl
    send = impl.SendGoalService.Request(goal=Fibonacci.Goal(order=5))
    send.goal_id.uuid = list(range(16))  # rclpy's code fills it from uuid.uuid4().bytes
    assert bytes(send.goal_id.uuid) == bytes(range(16))
    assert impl.SendGoalService.__ros_type__ == "example_interfaces/action/Fibonacci_SendGoal"
    assert impl.GetResultService.Response().status == GoalStatus.STATUS_UNKNOWN
    assert fields(impl.FeedbackMessage) == ["goal_id", "feedback"]
    assert impl.CancelGoalService is CancelGoal and impl.GoalStatusMessage is GoalStatusArray
    assert CancelGoal.Response.ERROR_GOAL_TERMINATED == 3 and fields(GoalInfo) == ["goal_id", "stamp"]
    assert UUID().uuid == bytes(16)
    for name in ("Fibonacci_Goal", "Fibonacci_SendGoal", "Fibonacci_SendGoal_Request", "Fibonacci_FeedbackMessage"):
        assert hasattr(importlib.import_module("example_interfaces.action"), name)


@pytest.mark.parametrize(
    "module",
    ["example_interfaces.msg", "example_interfaces.srv", "example_interfaces.action", "rospy_tutorials.srv",
     "turtlesim.msg", "turtlesim.srv", "turtlesim.action", "actionlib.msg", "actionlib_tutorials.msg",
     "actionlib_msgs.msg", "action_msgs.msg", "action_msgs.srv", "unique_identifier_msgs.msg"],
)  # fmt: skip
def test_every_view_holds_only_its_kind(module: str) -> None:
    kind = {"msg": Message, "srv": ServiceType, "action": ActionType}[module.rsplit(".", 1)[1]]
    view = importlib.import_module(module)
    tops = [getattr(view, name) for name in view.__all__ if "_" not in name and not name.endswith(("Request", "Response"))]
    assert tops and all(issubclass(cls, kind) for cls in tops), module


def test_a_facade_that_is_also_a_message_package_keeps_its_messages(monkeypatch: pytest.MonkeyPatch) -> None:
    # actionlib is an API (a façade, when Skydeck has one) and a message package (actionlib.msg)
    from services.ros import imports

    monkeypatch.setitem(imports.FACADES, "actionlib", "services.ros.rospy")  # any façade stands in
    disable_ros_imports()
    enable_ros_imports()
    import actionlib
    from actionlib.msg import TestGoal

    assert hasattr(actionlib, "init_node") and TestGoal(goal=1).goal == 1
