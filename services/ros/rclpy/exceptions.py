"""``rclpy.exceptions``: the parameter errors (the SDK's, with rclpy's names) and the rest."""

from __future__ import annotations

from services.ros.rclpy.context import NotInitializedException
from services.ros.rclpy.qos import InvalidQoSProfileException
from services.ros.rclpy.timer import ROSInterruptException
from services.runtime.parameters import (
    InvalidParameterException,
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterAlreadyDeclaredException,
    ParameterException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from shared_models.names import InvalidNameError

__all__ = [
    "InvalidNamespaceException",
    "InvalidNodeNameException",
    "InvalidParameterException",
    "InvalidParameterTypeException",
    "InvalidParameterValueException",
    "InvalidQoSProfileException",
    "InvalidServiceNameException",
    "InvalidTopicNameException",
    "NotInitializedException",
    "ParameterAlreadyDeclaredException",
    "ParameterException",
    "ParameterImmutableException",
    "ParameterNotDeclaredException",
    "ParameterUninitializedException",
    "ROSInterruptException",
]

# Names are checked once, by shared_models; rclpy's several names are that one error.
InvalidNodeNameException = InvalidNameError
InvalidNamespaceException = InvalidNameError
InvalidTopicNameException = InvalidNameError
InvalidServiceNameException = InvalidNameError
