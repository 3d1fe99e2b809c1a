"""rosapi_msgs' time, version, actions and interfaces."""

from __future__ import annotations

from typing import Any

from pydantic import Field, field_validator, model_serializer
from pydantic_core.core_schema import SerializerFunctionWrapHandler

from shared_models._message import Int32, Message, ServiceType, String
from shared_models.builtin_interfaces import Time


class GetTimeRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/GetTime_Request"


class GetTimeResponse(Message):
    """The time, with ROS 1's ``secs``/``nsecs`` beside ROS 2's ``sec``/``nanosec`` in JSON:
    roslibpy and older roslibjs read the first, ROS 2 clients the second."""

    __ros_type__ = "rosapi_msgs/srv/GetTime_Response"

    time: Time = Field(default_factory=Time)

    @field_validator("time", mode="before")
    @classmethod
    def _ros2_fields_only(cls, value: Any) -> Any:
        if isinstance(value, dict) and ("secs" in value or "nsecs" in value):
            return {key: item for key, item in value.items() if key not in ("secs", "nsecs")}
        return value

    @model_serializer(mode="wrap")
    def _with_ros1_fields(self, handler: SerializerFunctionWrapHandler) -> dict[str, Any]:
        data: dict[str, Any] = handler(self)
        time = data.get("time")
        if isinstance(time, dict):
            time["secs"], time["nsecs"] = time["sec"], time["nanosec"]
        return data


class GetROSVersionRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/GetROSVersion_Request"


class GetROSVersionResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/GetROSVersion_Response"

    version: Int32 = 2
    distro: String = ""


class GetTime(ServiceType):
    """The time: sim time while /clock runs, else the wall clock."""

    __ros_type__ = "rosapi_msgs/srv/GetTime"
    Request = GetTimeRequest
    Response = GetTimeResponse


class GetROSVersion(ServiceType):
    """The ROS version and distribution clients should expect."""

    __ros_type__ = "rosapi_msgs/srv/GetROSVersion"
    Request = GetROSVersionRequest
    Response = GetROSVersionResponse


class GetActionServersRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/GetActionServers_Request"


class GetActionServersResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/GetActionServers_Response"

    action_servers: list[String] = Field(default_factory=list)


class GetActionServers(ServiceType):
    """Every action with a server: ROS 2's, and ROS 1 actionlib's (by their five topics)."""

    __ros_type__ = "rosapi_msgs/srv/GetActionServers"
    Request = GetActionServersRequest
    Response = GetActionServersResponse


class ActionTypeRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/ActionType_Request"

    action: String = ""


class ActionTypeResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/ActionType_Response"

    type: String = ""


class ActionType_(ServiceType):  # "ActionType" is the base class of every action type
    """The type of one ROS 2 action."""

    __ros_type__ = "rosapi_msgs/srv/ActionType"
    Request = ActionTypeRequest
    Response = ActionTypeResponse


class InterfacesRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/Interfaces_Request"


class InterfacesResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/Interfaces_Response"

    interfaces: list[String] = Field(default_factory=list)


class Interfaces(ServiceType):
    """Every message, service and action type the core knows."""

    __ros_type__ = "rosapi_msgs/srv/Interfaces"
    Request = InterfacesRequest
    Response = InterfacesResponse
