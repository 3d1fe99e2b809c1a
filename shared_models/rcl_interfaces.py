"""rcl_interfaces: Log (the ``/rosout`` message) and node parameters: their types, values,
descriptors, events and the services ``ros2 param`` calls (``/NODE/get_parameters``...)."""

from __future__ import annotations

from typing import Annotated, ClassVar

from annotated_types import Interval
from pydantic import BeforeValidator, ConfigDict, Field, Strict

from shared_models._message import (
    Bool,
    ByteArray,
    Declared,
    Float64,
    Message,
    RosPrimitive,
    ServiceType,
    String,
    UInt8,
    UInt8Array,
    UInt32,
    UInt64,
)
from shared_models.builtin_interfaces import Time

__all__ = [
    "DescribeParameters",
    "DescribeParametersRequest",
    "DescribeParametersResponse",
    "FloatingPointRange",
    "GetParameterTypes",
    "GetParameterTypesRequest",
    "GetParameterTypesResponse",
    "GetParameters",
    "GetParametersRequest",
    "GetParametersResponse",
    "IntegerRange",
    "ListParameters",
    "ListParametersRequest",
    "ListParametersResponse",
    "ListParametersResult",
    "Log",
    "Parameter",
    "ParameterDescriptor",
    "ParameterEvent",
    "ParameterType",
    "ParameterValue",
    "SetParameters",
    "SetParametersAtomically",
    "SetParametersAtomicallyRequest",
    "SetParametersAtomicallyResponse",
    "SetParametersRequest",
    "SetParametersResponse",
    "SetParametersResult",
]

_BYTES_AS_BASE64 = ConfigDict(ser_json_bytes="base64", val_json_bytes="base64")


def _integral(value: object) -> object:
    return int(value) if type(value) is float and value.is_integer() else value


# Parameters travel to and from every kind of client (the CLI, browsers, rosbridge and Foxglove
# clients in JavaScript), so their integers are the ones JSON carries exactly (|n| <= 2**53 - 1,
# JavaScript's safe integers; bounds past that are compared as floats by JSON Schema validators),
# and a number written 5.0 is the integer 5, as JSON Schema counts it. Not for hot messages: the
# conversion costs a Python call per field.
_JSON_SAFE = 2**53 - 1
_ParamInt64 = Annotated[int, Strict(), RosPrimitive("int64"), Interval(ge=-_JSON_SAFE, le=_JSON_SAFE), BeforeValidator(_integral)]
_ParamUInt64 = Annotated[int, Strict(), RosPrimitive("uint64"), Interval(ge=0, le=_JSON_SAFE), BeforeValidator(_integral)]
_ParamUInt8 = Annotated[UInt8, BeforeValidator(_integral)]


class Log(Message):
    """One log record of a node, as published on ``/rosout``; ``level`` is one of the constants."""

    __ros_type__ = "rcl_interfaces/msg/Log"
    __ros_comment__ = (
        "# Severity level constants: they follow Python's logging levels.\n"
        "# The name of the node is in name, the logged text in msg."
    )
    __ros_constants__ = ("DEBUG", "INFO", "WARN", "ERROR", "FATAL")

    DEBUG: ClassVar[UInt8] = 10
    INFO: ClassVar[UInt8] = 20
    WARN: ClassVar[UInt8] = 30
    ERROR: ClassVar[UInt8] = 40
    FATAL: ClassVar[UInt8] = 50

    stamp: Time = Field(default_factory=Time)
    level: UInt8 = 0
    name: String = ""
    msg: String = ""
    file: String = ""
    function: String = ""
    line: UInt32 = 0


class ParameterType(Message):
    """The parameter types, as constants (the message has no fields)."""

    __ros_type__ = "rcl_interfaces/msg/ParameterType"
    __ros_comment__ = (
        "# These types correspond to the value that is set in the ParameterValue message.\n"
        "# PARAMETER_NOT_SET: the parameter does not exist or has no value."
    )
    __ros_constants__ = (
        "PARAMETER_NOT_SET",
        "PARAMETER_BOOL",
        "PARAMETER_INTEGER",
        "PARAMETER_DOUBLE",
        "PARAMETER_STRING",
        "PARAMETER_BYTE_ARRAY",
        "PARAMETER_BOOL_ARRAY",
        "PARAMETER_INTEGER_ARRAY",
        "PARAMETER_DOUBLE_ARRAY",
        "PARAMETER_STRING_ARRAY",
    )

    PARAMETER_NOT_SET: ClassVar[UInt8] = 0
    PARAMETER_BOOL: ClassVar[UInt8] = 1
    PARAMETER_INTEGER: ClassVar[UInt8] = 2
    PARAMETER_DOUBLE: ClassVar[UInt8] = 3
    PARAMETER_STRING: ClassVar[UInt8] = 4
    PARAMETER_BYTE_ARRAY: ClassVar[UInt8] = 5
    PARAMETER_BOOL_ARRAY: ClassVar[UInt8] = 6
    PARAMETER_INTEGER_ARRAY: ClassVar[UInt8] = 7
    PARAMETER_DOUBLE_ARRAY: ClassVar[UInt8] = 8
    PARAMETER_STRING_ARRAY: ClassVar[UInt8] = 9


class ParameterValue(Message):
    """A parameter's value: ``type`` (a ParameterType constant) says which one field holds it.

    ``byte_array_value`` travels in JSON as base64, as every byte array in Skydeck does.
    """

    model_config = _BYTES_AS_BASE64

    __ros_type__ = "rcl_interfaces/msg/ParameterValue"
    __ros_comment__ = (
        "# Used to determine which of the next *_value fields are set.\n"
        "# ParameterType.PARAMETER_NOT_SET indicates that the parameter was not set\n"
        "# (if gotten) or is uninitialized.\n"
        "# Values are enumerated in `ParameterType.msg`."
    )

    type: _ParamUInt8 = 0
    bool_value: Bool = False
    integer_value: _ParamInt64 = 0
    double_value: Float64 = 0.0
    string_value: String = ""
    byte_array_value: ByteArray = b""
    bool_array_value: list[Bool] = Field(default_factory=list)
    integer_array_value: list[_ParamInt64] = Field(default_factory=list)
    double_array_value: list[Float64] = Field(default_factory=list)
    string_array_value: list[String] = Field(default_factory=list)


class Parameter(Message):
    """A named parameter value, as set or reported by a node."""

    __ros_type__ = "rcl_interfaces/msg/Parameter"
    __ros_comment__ = "# This is the message to communicate a parameter's name and value."

    name: String = ""  # The full name of the parameter.
    value: ParameterValue = Field(default_factory=ParameterValue)


class FloatingPointRange(Message):
    """The allowed range of a float parameter; ``step`` 0 means any value in it."""

    __ros_type__ = "rcl_interfaces/msg/FloatingPointRange"
    __ros_comment__ = (
        "# Represents bounds and a step value for a floating point typed parameter."
    )

    from_value: Float64 = 0.0  # Start value for valid values, inclusive.
    to_value: Float64 = 0.0  # End value for valid values, inclusive.
    step: Float64 = 0.0  # Size of valid steps between the from and to bound; 0 means continuous.


class IntegerRange(Message):
    """The allowed range of an integer parameter; ``step`` 0 means any value in it."""

    __ros_type__ = "rcl_interfaces/msg/IntegerRange"
    __ros_comment__ = "# Represents bounds and a step value for an integer typed parameter."

    from_value: _ParamInt64 = 0  # Start value for valid values, inclusive.
    to_value: _ParamInt64 = 0  # End value for valid values, inclusive.
    step: _ParamUInt64 = 0  # Size of valid steps between the from and to bound; 0 means continuous.


class ParameterDescriptor(Message):
    """What a node says about one of its parameters: type, description, constraints and range.

    Example (rclpy)::

        self.declare_parameter("speed", 0.2, ParameterDescriptor(description="m/s"))
    """

    __ros_type__ = "rcl_interfaces/msg/ParameterDescriptor"
    __ros_comment__ = "# This is the message to communicate a parameter's descriptor."

    name: String = ""  # The name of the parameter.
    type: _ParamUInt8 = 0  # Enum values are defined in the `ParameterType.msg` message.
    description: String = ""  # Description of the parameter, visible from introspection tools.
    additional_constraints: String = ""  # Plain English description of additional constraints.
    read_only: Annotated[Bool, Declared()] = False  # If true, the value cannot change.
    dynamic_typing: Annotated[Bool, Declared()] = False  # If true, the type may change.
    # At most one range, and only for a parameter of that type.
    floating_point_range: list[FloatingPointRange] = Field(default_factory=list, max_length=1)
    integer_range: list[IntegerRange] = Field(default_factory=list, max_length=1)


class SetParametersResult(Message):
    """Whether a parameter change was accepted, and why not (what an on-set callback returns)."""

    __ros_type__ = "rcl_interfaces/msg/SetParametersResult"
    __ros_comment__ = (
        "# A true value of the same index indicates that the parameter was set\n"
        "# successfully. A false value indicates the change was rejected."
    )

    successful: Bool = False
    reason: String = ""  # Reason why the setting was either successful or a failure.


class ListParametersResult(Message):
    """The parameter names and prefixes a node has (the answer of list_parameters)."""

    __ros_type__ = "rcl_interfaces/msg/ListParametersResult"
    __ros_comment__ = "# The resulting parameters under the given prefixes."

    names: list[String] = Field(default_factory=list)
    prefixes: list[String] = Field(default_factory=list)  # The resulting prefixes.


class ParameterEvent(Message):
    """The parameters of one node that were added, changed or deleted (``/parameter_events``)."""

    __ros_type__ = "rcl_interfaces/msg/ParameterEvent"
    __ros_comment__ = (
        "# This message contains a parameter event.\n"
        "# Because the parameter event was an atomic update, a specific parameter name\n"
        "# can only be in one of the three sets."
    )

    stamp: Time = Field(default_factory=Time)  # The time stamp when this parameter event occurred.
    node: String = ""  # Fully qualified ROS path to node.
    new_parameters: list[Parameter] = Field(default_factory=list)
    changed_parameters: list[Parameter] = Field(default_factory=list)
    deleted_parameters: list[Parameter] = Field(default_factory=list)


# The parameter services every ROS 2 node offers, under /NODE/<name in snake case>.


class GetParametersRequest(Message):
    """The names of the parameters to get."""

    __ros_type__ = "rcl_interfaces/srv/GetParameters_Request"

    names: list[String] = Field(default_factory=list)  # A list of parameter names to get.


class GetParametersResponse(Message):
    """The values, in the order asked (PARAMETER_NOT_SET for an unknown name)."""

    __ros_type__ = "rcl_interfaces/srv/GetParameters_Response"

    values: list[ParameterValue] = Field(default_factory=list)


class GetParameters(ServiceType):
    """Get the values of a node's parameters."""

    __ros_type__ = "rcl_interfaces/srv/GetParameters"
    Request = GetParametersRequest
    Response = GetParametersResponse


class SetParametersRequest(Message):
    """The parameters to set, each on its own."""

    __ros_type__ = "rcl_interfaces/srv/SetParameters_Request"

    parameters: list[Parameter] = Field(default_factory=list)  # A list of parameters to set.


class SetParametersResponse(Message):
    """One result per parameter, in the order asked."""

    __ros_type__ = "rcl_interfaces/srv/SetParameters_Response"

    results: list[SetParametersResult] = Field(default_factory=list)


class SetParameters(ServiceType):
    """Set a node's parameters one by one (each may be refused on its own)."""

    __ros_type__ = "rcl_interfaces/srv/SetParameters"
    Request = SetParametersRequest
    Response = SetParametersResponse


class SetParametersAtomicallyRequest(Message):
    """The parameters to set together."""

    __ros_type__ = "rcl_interfaces/srv/SetParametersAtomically_Request"

    parameters: list[Parameter] = Field(default_factory=list)  # parameters to set atomically


class SetParametersAtomicallyResponse(Message):
    """One result for all: either every parameter was set or none."""

    __ros_type__ = "rcl_interfaces/srv/SetParametersAtomically_Response"

    result: SetParametersResult = Field(default_factory=SetParametersResult)


class SetParametersAtomically(ServiceType):
    """Set several of a node's parameters all at once, or none of them."""

    __ros_type__ = "rcl_interfaces/srv/SetParametersAtomically"
    Request = SetParametersAtomicallyRequest
    Response = SetParametersAtomicallyResponse


class ListParametersRequest(Message):
    """Which parameters to list: under ``prefixes`` (all when empty), ``depth`` levels down."""

    __ros_type__ = "rcl_interfaces/srv/ListParameters_Request"
    __ros_constants__ = ("DEPTH_RECURSIVE",)

    DEPTH_RECURSIVE: ClassVar[UInt64] = 0  # Recursively get parameters with all depths.

    prefixes: list[String] = Field(default_factory=list)  # The list of parameter prefixes to query.
    depth: _ParamUInt64 = 0  # Relative depth from given prefixes to return.


class ListParametersResponse(Message):
    """The names and prefixes found."""

    __ros_type__ = "rcl_interfaces/srv/ListParameters_Response"

    result: ListParametersResult = Field(default_factory=ListParametersResult)


class ListParameters(ServiceType):
    """List a node's parameter names."""

    __ros_type__ = "rcl_interfaces/srv/ListParameters"
    Request = ListParametersRequest
    Response = ListParametersResponse


class DescribeParametersRequest(Message):
    """The names of the parameters to describe."""

    __ros_type__ = "rcl_interfaces/srv/DescribeParameters_Request"

    names: list[String] = Field(default_factory=list)  # parameters to get the descriptors of


class DescribeParametersResponse(Message):
    """The descriptors, in the order asked."""

    __ros_type__ = "rcl_interfaces/srv/DescribeParameters_Response"

    descriptors: list[ParameterDescriptor] = Field(default_factory=list)


class DescribeParameters(ServiceType):
    """Get the descriptors of a node's parameters."""

    __ros_type__ = "rcl_interfaces/srv/DescribeParameters"
    Request = DescribeParametersRequest
    Response = DescribeParametersResponse


class GetParameterTypesRequest(Message):
    """The names of the parameters whose types to get."""

    __ros_type__ = "rcl_interfaces/srv/GetParameterTypes_Request"

    names: list[String] = Field(default_factory=list)  # A list of parameter names.


class GetParameterTypesResponse(Message):
    """One ParameterType constant per name, in the order asked; base64 in JSON (``uint8[]``)."""

    model_config = _BYTES_AS_BASE64

    __ros_type__ = "rcl_interfaces/srv/GetParameterTypes_Response"

    types: UInt8Array = b""


class GetParameterTypes(ServiceType):
    """Get the types of a node's parameters."""

    __ros_type__ = "rcl_interfaces/srv/GetParameterTypes"
    Request = GetParameterTypesRequest
    Response = GetParameterTypesResponse
