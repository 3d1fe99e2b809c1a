"""rosapi's parameter services, answered as ROS 1's and ROS 2's rosapi answer them.

A name with a node (``/tuned:max_speed``, or ``/tuned.max_speed``) is that ROS 2 node's
parameter, reached through the node's own parameter services (:mod:`services.protocols.parameters`);
a name without one (``test_param``, ``/robot/max_speed``) is ROS 1's, on the core's parameter
server, relative names read from ``/`` as rosapi's node reads them. So roslibjs's and roslibpy's
``Param`` work as against either ROS.

- ``get_param``: the value as JSON text; an unset one answers the request's default (``default``
  in ROS 1's request, ``default_value`` in ROS 2's: JSON text, or plain text taken as a string),
  and with no default JSON ``null``, as ROS 1's rosapi answers (``successful`` false, and why).
- ``set_param``: the value as JSON text; ``delete_param`` (a ROS 1 name: a ROS 2 parameter is its
  node's, as ROS 2's rosapi cannot undeclare another node's either), ``has_param``,
  ``search_param`` (rospy's, from ``/``), ``get_param_names`` (ROS 1's leaves, then each node's).

In a class, each is done with the rights of whoever called rosapi (:data:`CALLER`), as the core's
own routes do them: a node's parameters through the fenced call path, a ROS 1 name read
(``READ``) or written (``SET_PARAMETER``) only where the caller's token may (a student: under
their namespace); a refusal is the response's ``reason``.
"""

from __future__ import annotations

import json
from typing import Any

from services.access import AccessRefused, Verb
from services.core.access import CoreAccess
from services.core.service_calls import CALLER
from services.protocols.parameters import ParameterError, Parameters, ParameterValueJson, split_name
from shared_models import rosapi_msgs as rosapi

__all__ = ["RosapiParams"]


def _is_node_parameter(name: str) -> bool:
    """``/node:param`` or ``/node.param`` (a ROS 1 name has neither ``:`` nor ``.``)."""
    return ":" in name or "." in name


def _ros1_name(name: str) -> str:
    """A ROS 1 parameter name as the ``/rosapi`` node resolves it: from ``/``."""
    if name.startswith("~"):
        return "/rosapi/" + name[1:].lstrip("/")
    return "/" + name.lstrip("/")


def _default(text: str) -> Any:
    """A request's default: JSON text, or plain text as a string (rosapi's reading); none is None."""
    if text == "":
        return None
    try:
        return json.loads(text)
    except ValueError:
        return text


class RosapiParams:
    """The handlers (see the module docstring)."""

    def __init__(self, access: CoreAccess) -> None:
        self._tree = access.rosparam
        self._nodes = Parameters(
            access.registry, lambda service, body: access.calls.call(service, body, caller=CALLER.get())
        )

    async def get_param(self, request: rosapi.GetParamRequest) -> rosapi.GetParamResponse:
        name = request.name
        unset = json.dumps(_default(request.default_value))
        try:
            if _is_node_parameter(name):
                split_name(name)
                values = await self._nodes.get([name])
                if not values:
                    return rosapi.GetParamResponse(value=unset, reason=f"{name} is not set")
                value = values[0].value
            else:
                _check(Verb.READ, _ros1_name(name))
                value = self._tree.get(_ros1_name(name))
        except (ParameterError, ValueError, AccessRefused) as error:
            return rosapi.GetParamResponse(value=unset, reason=str(error))
        except KeyError:
            return rosapi.GetParamResponse(value=unset, reason=f"{_ros1_name(name)} is not set")
        return rosapi.GetParamResponse(value=json.dumps(value), successful=True)

    async def set_param(self, request: rosapi.SetParamRequest) -> rosapi.SetParamResponse:
        try:
            value = json.loads(request.value)
        except ValueError:
            return rosapi.SetParamResponse(reason=f"the value must be JSON text, got {request.value!r}")
        try:
            if not _is_node_parameter(request.name):
                _check(Verb.SET_PARAMETER, _ros1_name(request.name))
                self._tree.set(_ros1_name(request.name), value)
                return rosapi.SetParamResponse(successful=True)
            (result,) = await self._nodes.set([ParameterValueJson(request.name, value)])
        except (ParameterError, ValueError, AccessRefused) as error:
            return rosapi.SetParamResponse(reason=str(error))
        return rosapi.SetParamResponse(successful=result[1], reason=result[2])

    async def delete_param(self, request: rosapi.DeleteParamRequest) -> rosapi.DeleteParamResponse:
        name = request.name
        if _is_node_parameter(name):
            return rosapi.DeleteParamResponse(
                reason=f"{name} is a parameter of its node: a node's parameters cannot be deleted from outside it (set it instead)"
            )
        try:
            _check(Verb.SET_PARAMETER, _ros1_name(name))
            self._tree.delete(_ros1_name(name))
        except (ValueError, AccessRefused) as error:
            return rosapi.DeleteParamResponse(reason=str(error))
        except KeyError:
            return rosapi.DeleteParamResponse(reason=f"{_ros1_name(name)} is not set")
        return rosapi.DeleteParamResponse(successful=True)

    async def has_param(self, request: rosapi.HasParamRequest) -> rosapi.HasParamResponse:
        name = request.name
        try:
            if _is_node_parameter(name):
                split_name(name)
                return rosapi.HasParamResponse(exists=bool(await self._nodes.get([name])))
            self._tree.get(_ros1_name(name))
        except (ParameterError, ValueError, KeyError):
            return rosapi.HasParamResponse(exists=False)
        return rosapi.HasParamResponse(exists=True)

    def search_param(self, request: rosapi.SearchParamRequest) -> rosapi.SearchParamResponse:
        """rospy's ``search_param`` from ``/``: the name, if its first part is set there."""
        name = _ros1_name(request.name)
        first = "/" + name.strip("/").split("/", 1)[0]
        try:
            self._tree.get(first)
        except (KeyError, ValueError):
            return rosapi.SearchParamResponse()
        return rosapi.SearchParamResponse(global_name=name)

    async def get_param_names(self, request: Any) -> rosapi.GetParamNamesResponse:
        ros1 = sorted(_leaves("", self._tree.get("/")))
        nodes = [name.replace(".", ":", 1) for name in await self._nodes.names()]
        return rosapi.GetParamNamesResponse(names=ros1 + nodes)


def _check(verb: Verb, name: str) -> None:
    """AccessRefused unless rosapi's caller may ``verb`` the ROS 1 parameter ``name``."""
    CALLER.get().check(verb, name)


def _leaves(prefix: str, tree: Any) -> list[str]:
    """Every parameter's full name under ``prefix`` (a namespace's mapping is not one itself)."""
    names: list[str] = []
    for key, value in tree.items():
        name = f"{prefix}/{key}"
        names += _leaves(name, value) if isinstance(value, dict) and value else [name]
    return names
