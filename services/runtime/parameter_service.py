"""The parameter services every node offers, named and typed as ROS 2's: ``/NODE/get_parameters``,
``/NODE/set_parameters``... (``rcl_interfaces/srv/*``), so ``skydeck param``, ``ros2 param``-style
tools, the dashboard and the protocol adapters read and change any node's parameters the same way.

A change refused by the node (wrong type, read-only, out of range, an on-set callback's "no") is
an answer with ``successful: false`` and the reason, never an HTTP error. An on-set callback that
raises is logged with its traceback (the user's file and line) and refuses the change; the node
keeps running.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from services.runtime.parameter import Parameter
from services.runtime.parameters import NodeParameters, ParameterException
from shared_models import Message, ServiceType
from shared_models.rcl_interfaces import (
    DescribeParameters,
    DescribeParametersRequest,
    DescribeParametersResponse,
    GetParameters,
    GetParametersRequest,
    GetParametersResponse,
    GetParameterTypes,
    GetParameterTypesRequest,
    GetParameterTypesResponse,
    ListParameters,
    ListParametersRequest,
    ListParametersResponse,
    ParameterDescriptor,
    ParameterValue,
    SetParameters,
    SetParametersAtomically,
    SetParametersAtomicallyRequest,
    SetParametersAtomicallyResponse,
    SetParametersRequest,
    SetParametersResponse,
    SetParametersResult,
)
from shared_models.rcl_interfaces import Parameter as ParameterMsg

__all__ = ["PARAMETER_EVENTS", "PARAMETER_SERVICES", "is_parameter_service", "parameter_services"]

PARAMETER_EVENTS = "/parameter_events"
"""Where every node publishes its ``rcl_interfaces/msg/ParameterEvent``s."""

PARAMETER_SERVICES: dict[str, type[ServiceType]] = {
    "describe_parameters": DescribeParameters,
    "get_parameter_types": GetParameterTypes,
    "get_parameters": GetParameters,
    "list_parameters": ListParameters,
    "set_parameters": SetParameters,
    "set_parameters_atomically": SetParametersAtomically,
}
"""The services by their name under the node's (``/ai/get_parameters``), as in ROS 2."""


def is_parameter_service(node_name: str, service_name: str) -> bool:
    """Whether ``service_name`` is one of ``node_name``'s parameter services."""
    node, _, verb = service_name.rpartition("/")
    return node == node_name and verb in PARAMETER_SERVICES


def parameter_services(
    node_name: str, parameters: NodeParameters, logger: logging.Logger
) -> list[tuple[type[ServiceType], str, Callable[[Any], Message]]]:
    """(type, name, handler) of each parameter service of ``node_name``, for ``create_service``."""
    handlers = _Handlers(parameters, logger)
    by_verb: dict[str, Callable[[Any], Message]] = {
        "describe_parameters": handlers.describe,
        "get_parameter_types": handlers.get_types,
        "get_parameters": handlers.get,
        "list_parameters": handlers.list_names,
        "set_parameters": handlers.set,
        "set_parameters_atomically": handlers.set_atomically,
    }
    return [(PARAMETER_SERVICES[verb], f"{node_name}/{verb}", handler) for verb, handler in by_verb.items()]


class _Handlers:
    """The six handlers, over one node's :class:`NodeParameters`."""

    def __init__(self, parameters: NodeParameters, logger: logging.Logger) -> None:
        self._parameters = parameters
        self._logger = logger

    def get(self, request: GetParametersRequest) -> GetParametersResponse:
        return GetParametersResponse(values=[self._value(name) for name in request.names])

    def _value(self, name: str) -> ParameterValue:
        try:
            return self._parameters.get(name).get_parameter_value()
        except ParameterException:
            return ParameterValue()  # PARAMETER_NOT_SET: unknown, or no value yet

    def get_types(self, request: GetParameterTypesRequest) -> GetParameterTypesResponse:
        return GetParameterTypesResponse(types=bytes(self._value(name).type for name in request.names))

    def describe(self, request: DescribeParametersRequest) -> DescribeParametersResponse:
        parameters = self._parameters
        return DescribeParametersResponse(
            descriptors=[
                parameters.describe(name) if parameters.has(name) else ParameterDescriptor(name=name)
                for name in request.names
            ]
        )

    def list_names(self, request: ListParametersRequest) -> ListParametersResponse:
        return ListParametersResponse(result=self._parameters.list_names(request.prefixes, request.depth))

    def set(self, request: SetParametersRequest) -> SetParametersResponse:
        return SetParametersResponse(results=[self._set([parameter]) for parameter in request.parameters])

    def set_atomically(self, request: SetParametersAtomicallyRequest) -> SetParametersAtomicallyResponse:
        return SetParametersAtomicallyResponse(result=self._set(request.parameters))

    def _set(self, messages: list[ParameterMsg]) -> SetParametersResult:
        try:
            parameters = [Parameter.from_parameter_msg(message) for message in messages]
        except (TypeError, ValueError) as error:
            return SetParametersResult(successful=False, reason=str(error))
        try:
            return self._parameters.set_atomically(parameters)
        except ParameterException as error:
            return SetParametersResult(successful=False, reason=str(error))
        except Exception as error:  # the node's own on-set callback raised: its traceback, then refuse
            self._logger.exception("an on-set parameters callback raised; the change is refused, the node keeps running")
            return SetParametersResult(
                successful=False, reason=f"the node's on-set callback raised {type(error).__name__}: {error}"
            )
