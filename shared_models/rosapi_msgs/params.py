"""rosapi_msgs' parameters: values as JSON text, as rosapi carries them.

A name with a node (``/node:param``, or ``/node.param``) is a ROS 2 node's parameter; a name
without one (``/robot/max_speed``) is ROS 1's, on the core's parameter server.
"""

from __future__ import annotations

from typing import Any

from pydantic import Field, model_validator

from shared_models._message import Bool, Message, ServiceType, String


class GetParamRequest(Message):
    """ROS 2's request; ROS 1's names its second field ``default``, which is read as ``default_value``."""

    __ros_type__ = "rosapi_msgs/srv/GetParam_Request"

    name: String = ""  # "/node:param" (or "/node.param"): a node's; "/a/b": ROS 1's
    default_value: String = ""  # JSON text (or plain text), answered when the parameter is not set

    @model_validator(mode="before")
    @classmethod
    def _ros1_default(cls, value: Any) -> Any:
        if isinstance(value, dict) and "default" in value and "default_value" not in value:
            value = {("default_value" if key == "default" else key): item for key, item in value.items()}
        return value


class GetParamResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/GetParam_Response"

    value: String = ""  # JSON text
    successful: Bool = False
    reason: String = ""


class SetParamRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/SetParam_Request"

    name: String = ""
    value: String = ""  # JSON text


class SetParamResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/SetParam_Response"

    successful: Bool = False
    reason: String = ""


class GetParamNamesRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/GetParamNames_Request"


class GetParamNamesResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/GetParamNames_Response"

    names: list[String] = Field(default_factory=list)


class GetParam(ServiceType):
    """One parameter's value as JSON text (``null`` when it is not set and no default is given)."""

    __ros_type__ = "rosapi_msgs/srv/GetParam"
    Request = GetParamRequest
    Response = GetParamResponse


class SetParam(ServiceType):
    """Set one parameter from JSON text."""

    __ros_type__ = "rosapi_msgs/srv/SetParam"
    Request = SetParamRequest
    Response = SetParamResponse


class GetParamNames(ServiceType):
    """Every parameter's name: ROS 1's, and each node's (``/node:param``)."""

    __ros_type__ = "rosapi_msgs/srv/GetParamNames"
    Request = GetParamNamesRequest
    Response = GetParamNamesResponse


class DeleteParamRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/DeleteParam_Request"

    name: String = ""


class DeleteParamResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/DeleteParam_Response"

    successful: Bool = False
    reason: String = ""


class DeleteParam(ServiceType):
    """Delete one parameter (a ROS 1 one: a ROS 2 node's parameters are the node's)."""

    __ros_type__ = "rosapi_msgs/srv/DeleteParam"
    Request = DeleteParamRequest
    Response = DeleteParamResponse


class HasParamRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/HasParam_Request"

    name: String = ""


class HasParamResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/HasParam_Response"

    exists: Bool = False


class HasParam(ServiceType):
    """Whether one parameter is set."""

    __ros_type__ = "rosapi_msgs/srv/HasParam"
    Request = HasParamRequest
    Response = HasParamResponse


class SearchParamRequest(Message):
    __ros_type__ = "rosapi_msgs/srv/SearchParam_Request"

    name: String = ""


class SearchParamResponse(Message):
    __ros_type__ = "rosapi_msgs/srv/SearchParam_Response"

    global_name: String = ""  # empty when no namespace up from / holds it


class SearchParam(ServiceType):
    """The full name of the nearest ROS 1 parameter called ``name`` (rospy's ``search_param``)."""

    __ros_type__ = "rosapi_msgs/srv/SearchParam"
    Request = SearchParamRequest
    Response = SearchParamResponse
