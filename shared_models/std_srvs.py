"""std_srvs: Trigger, Empty and SetBool.

Each service reads both ways: rclpy's ``Trigger.Request()`` and rospy's ``TriggerResponse()``.
The request and response messages are registered as ``std_srvs/srv/Trigger_Request`` and
``std_srvs/srv/Trigger_Response``, as ROS 2 names them.
"""

from __future__ import annotations

from shared_models._message import Bool, Message, ServiceType, String

__all__ = [
    "Empty",
    "EmptyRequest",
    "EmptyResponse",
    "SetBool",
    "SetBoolRequest",
    "SetBoolResponse",
    "Trigger",
    "TriggerRequest",
    "TriggerResponse",
]


class TriggerRequest(Message):
    """The (empty) request of Trigger."""

    __ros_type__ = "std_srvs/srv/Trigger_Request"


class TriggerResponse(Message):
    """The response of Trigger: whether it worked and a message for the caller."""

    __ros_type__ = "std_srvs/srv/Trigger_Response"

    success: Bool = False  # indicate successful run of triggered service
    message: String = ""  # informational, e.g. for error messages


class Trigger(ServiceType):
    """Run an action that needs no arguments (take off, land, reset)."""

    __ros_type__ = "std_srvs/srv/Trigger"
    Request = TriggerRequest
    Response = TriggerResponse


class EmptyRequest(Message):
    """The request of the Empty service."""

    __ros_type__ = "std_srvs/srv/Empty_Request"


class EmptyResponse(Message):
    """The response of the Empty service."""

    __ros_type__ = "std_srvs/srv/Empty_Response"


class Empty(ServiceType):
    """A service with no arguments and no result."""

    __ros_type__ = "std_srvs/srv/Empty"
    Request = EmptyRequest
    Response = EmptyResponse


class SetBoolRequest(Message):
    """The request of SetBool."""

    __ros_type__ = "std_srvs/srv/SetBool_Request"

    data: Bool = False  # e.g. for hardware enabling / disabling


class SetBoolResponse(Message):
    """The response of SetBool."""

    __ros_type__ = "std_srvs/srv/SetBool_Response"

    success: Bool = False  # indicate successful run of triggered service
    message: String = ""  # informational, e.g. for error messages


class SetBool(ServiceType):
    """Switch something on or off."""

    __ros_type__ = "std_srvs/srv/SetBool"
    Request = SetBoolRequest
    Response = SetBoolResponse
