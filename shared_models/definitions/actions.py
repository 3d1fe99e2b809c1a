"""An ``.action`` file's classes: its goal, result and feedback, and what ROS derives from them.

ROS 2 (``example_interfaces/action/Fibonacci``)::

    Fibonacci_Goal, Fibonacci_Result, Fibonacci_Feedback     the file's three parts
    Fibonacci_SendGoal       service: goal_id (unique_identifier_msgs/UUID), goal -> accepted, stamp
    Fibonacci_GetResult      service: goal_id -> status (int8), result
    Fibonacci_FeedbackMessage  message: goal_id, feedback
    Fibonacci                the action (an ActionType): .Goal, .Result, .Feedback, and rclpy's
                             .Impl.SendGoalService, GetResultService, FeedbackMessage,
                             CancelGoalService (action_msgs/CancelGoal), GoalStatusMessage
                             (action_msgs/GoalStatusArray)

ROS 1 (actionlib's messages, in the package's ``msg`` namespace)::

    FibonacciGoal, FibonacciResult, FibonacciFeedback
    FibonacciActionGoal      header, goal_id (actionlib_msgs/GoalID), goal
    FibonacciActionResult    header, status (actionlib_msgs/GoalStatus), result
    FibonacciActionFeedback  header, status, feedback
    FibonacciAction          action_goal, action_result, action_feedback
"""

from __future__ import annotations

import types
from collections.abc import Callable

from shared_models._message import ActionType, Message
from shared_models.definitions.builder import Resolver, message_class, service_class
from shared_models.definitions.parser import Definition, FieldSpec, FieldType, MessageSpec

__all__ = ["action_classes"]

_Make = Callable[[str, MessageSpec, str], type[Message]]  # (ROS name, spec, class name) -> class

_UUID = "unique_identifier_msgs/msg/UUID"
_TIME = "builtin_interfaces/msg/Time"
_HEADER = "std_msgs/msg/Header"
_GOAL_ID = "actionlib_msgs/msg/GoalID"
_GOAL_STATUS = "actionlib_msgs/msg/GoalStatus"


def _message(*fields: tuple[str, str]) -> MessageSpec:
    return MessageSpec(fields=tuple(FieldSpec(name, FieldType(base)) for name, base in fields))


def action_classes(definition: Definition, resolve: Resolver) -> list[type]:
    """Every class of an action (see the module docstring), registered under their ROS names."""
    base, short = definition.ros_type, definition.name
    goal_spec, result_spec, feedback_spec = definition.parts

    def make(ros_type: str, spec: MessageSpec, class_name: str) -> type[Message]:
        return message_class(ros_type, spec, resolve, definition=definition, class_name=class_name)

    goal = make(f"{base}_Goal", goal_spec, f"{short}_Goal")
    result = make(f"{base}_Result", result_spec, f"{short}_Result")
    feedback = make(f"{base}_Feedback", feedback_spec, f"{short}_Feedback")
    send_goal = service_class(
        f"{base}_SendGoal",
        _message(("goal_id", _UUID), ("goal", f"{base}_Goal")),
        _message(("accepted", "bool"), ("stamp", _TIME)),
        resolve,
        definition=definition,
        joiner="_",
    )
    get_result = service_class(
        f"{base}_GetResult",
        _message(("goal_id", _UUID)),
        _message(("status", "int8"), ("result", f"{base}_Result")),
        resolve,
        definition=definition,
        joiner="_",
    )
    feedback_message = make(
        f"{base}_FeedbackMessage", _message(("goal_id", _UUID), ("feedback", f"{base}_Feedback")), f"{short}_FeedbackMessage"
    )
    ros1 = _actionlib_classes(definition, make)
    impl = types.new_class(
        "Impl",
        exec_body=lambda ns: ns.update(
            __doc__=f"rclpy's names of the types behind {base}.",
            SendGoalService=send_goal[2],
            GetResultService=get_result[2],
            FeedbackMessage=feedback_message,
            CancelGoalService=resolve("action_msgs/srv/CancelGoal", FieldSpec("", FieldType(""))),
            GoalStatusMessage=resolve("action_msgs/msg/GoalStatusArray", FieldSpec("", FieldType(""))),
        ),
    )
    namespace = {
        "__module__": f"{definition.package}.action",
        "__qualname__": short,
        "__doc__": f"The action {base}.",
        "__ros_type__": base,
        "__ros_comment__": goal_spec.comment,
        "__ros_definition__": base,
        "Goal": goal,
        "Result": result,
        "Feedback": feedback,
        "SendGoal": send_goal[2],
        "GetResult": get_result[2],
        "FeedbackMessage": feedback_message,
        "Impl": impl,
    }
    action = types.new_class(short, (ActionType,), exec_body=lambda ns: ns.update(namespace))
    return [goal, result, feedback, *send_goal, *get_result, feedback_message, *ros1, action]


def _actionlib_classes(definition: Definition, build: _Make) -> list[type]:
    """ROS 1's messages of the action (actionlib's), in the package's ``msg`` namespace."""
    prefix = f"{definition.package}/msg/{definition.name}"
    short = definition.name
    made = []
    for part, spec in zip(("Goal", "Result", "Feedback"), definition.parts, strict=True):
        made.append(build(f"{prefix}{part}", spec, f"{short}{part}"))
    # Each part in its envelope: a goal with its ID, a result or feedback with its goal's status.
    for part, tag in (("Goal", ("goal_id", _GOAL_ID)), ("Result", ("status", _GOAL_STATUS)),
                      ("Feedback", ("status", _GOAL_STATUS))):  # fmt: skip
        envelope = _message(("header", _HEADER), tag, (part.lower(), f"{prefix}{part}"))
        made.append(build(f"{prefix}Action{part}", envelope, f"{short}Action{part}"))
    parts = [(f"action_{part.lower()}", f"{prefix}Action{part}") for part in ("Goal", "Result", "Feedback")]
    made.append(build(f"{prefix}Action", _message(*parts), f"{short}Action"))
    return made
