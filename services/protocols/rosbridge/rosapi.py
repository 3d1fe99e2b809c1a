"""rosapi: the services rosbridge clients call to look around, answered from the registry.

The core hosts them as the node ``/rosapi`` (a guest: see :mod:`services.core.guests`), so a
rosbridge client calls ``/rosapi/topics`` (or ``rosapi/topics``: names resolve against ``/``),
and so can ``curl -X POST http://CORE/rosapi/topics`` or any node. They answer as ROS 2's
rosapi (humble) does, with ROS 1's services beside (``search_param``, ``service_host``), so a
client written for either finds what it calls. Parameters are :mod:`.rosapi_params`'; the time is
``/clock``'s latest message while a simulator publishes it, else the wall clock (:mod:`.clock`).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from typing import Any
from urllib.parse import urlsplit

import services.protocols.rosbridge.clock as clock
from services.core.access import CoreAccess
from services.protocols import ROS_DISTRO
from services.protocols.rosbridge.rosapi_params import RosapiParams
from services.runtime.actions.names import actions_in_graph
from services.runtime.service import Service
from shared_models import (
    InvalidNameError,
    Message,
    ServiceType,
    UnknownInterfaceError,
    get_interface,
    interface_names,
    resolve_name,
)
from shared_models import rosapi_msgs as rosapi
from shared_models.interfaces import field_types
from shared_models.ros2msg import definition_text

__all__ = ["host_rosapi", "typedefs"]

_BRACKETS = re.compile(r"\[(<=)?(\d*)\]$")
_ACTIONLIB_TOPICS = frozenset({"goal", "cancel", "status", "feedback", "result"})


def host_rosapi(access: CoreAccess) -> None:
    """Serve the rosapi services as the guest node ``/rosapi``."""
    guest = access.guests.add("/rosapi", client="rosapi (answered by the core)")
    api = _Rosapi(access)
    params = RosapiParams(access)
    handlers: dict[str, tuple[type[ServiceType], Callable[[Any], Any]]] = {
        "topics": (rosapi.Topics, api.topics),
        "topics_for_type": (rosapi.TopicsForType, api.topics_for_type),
        "topic_type": (rosapi.TopicType, api.topic_type),
        "topics_and_raw_types": (rosapi.TopicsAndRawTypes, api.topics_and_raw_types),
        "publishers": (rosapi.Publishers, api.publishers),
        "subscribers": (rosapi.Subscribers, api.subscribers),
        "services": (rosapi.Services, api.services),
        "services_for_type": (rosapi.ServicesForType, api.services_for_type),
        "service_type": (rosapi.ServiceType_, api.service_type),
        "service_node": (rosapi.ServiceNode, api.service_node),
        "service_providers": (rosapi.ServiceProviders, api.service_providers),
        "service_host": (rosapi.ServiceHost, api.service_host),
        "action_servers": (rosapi.GetActionServers, api.action_servers),
        "action_type": (rosapi.ActionType_, api.action_type),
        "nodes": (rosapi.Nodes, api.nodes),
        "node_details": (rosapi.NodeDetails, api.node_details),
        "message_details": (rosapi.MessageDetails, api.message_details),
        "service_request_details": (rosapi.ServiceRequestDetails, api.service_request_details),
        "service_response_details": (rosapi.ServiceResponseDetails, api.service_response_details),
        "interfaces": (rosapi.Interfaces, api.interfaces),
        "get_param": (rosapi.GetParam, params.get_param),
        "set_param": (rosapi.SetParam, params.set_param),
        "delete_param": (rosapi.DeleteParam, params.delete_param),
        "has_param": (rosapi.HasParam, params.has_param),
        "search_param": (rosapi.SearchParam, params.search_param),
        "get_param_names": (rosapi.GetParamNames, params.get_param_names),
        "get_time": (rosapi.GetTime, api.get_time),
        "get_ros_version": (rosapi.GetROSVersion, api.get_ros_version),
    }
    for name, (srv_type, handler) in handlers.items():
        guest.serves(Service(srv_type, f"/rosapi/{name}", handler))


def typedefs(cls: type[Message]) -> list[rosapi.TypeDef]:
    """``cls`` and every message type inside it, as rosapi describes them (``cls`` first)."""
    found: dict[str, rosapi.TypeDef] = {}
    pending = [cls]
    while pending:
        current = pending.pop(0)
        if current.__ros_type__ in found:
            continue
        names, types, lengths, examples = [], [], [], []
        for name, text, nested in field_types(current):
            bracket = _BRACKETS.search(text)
            length = -1 if bracket is None else (int(bracket.group(2)) if bracket.group(2) and not bracket.group(1) else 0)
            base = text[: bracket.start()] if bracket else text
            names.append(name)
            types.append(nested.__ros_type__ if nested is not None else base)
            lengths.append(length)
            examples.append(_example(current, name, nested is not None, length))
            if nested is not None:
                pending.append(nested)
        constants = current.__ros_constants__
        found[current.__ros_type__] = rosapi.TypeDef(
            type=current.__ros_type__,
            fieldnames=names,
            fieldtypes=types,
            fieldarraylen=lengths,
            examples=examples,
            constnames=list(constants),
            constvalues=[str(getattr(current, constant)) for constant in constants],
        )
    return list(found.values())


def _example(cls: type[Message], field: str, nested: bool, length: int) -> str:
    if length >= 0:
        return "[]"
    if nested:
        return "{}"
    default = cls.model_fields[field].default
    return json.dumps(default) if isinstance(default, bool | int | float | str) else ""


def _absolute(name: str) -> str:
    try:
        return resolve_name(name)
    except InvalidNameError:
        return ""


def _same_type(a: str, b: str) -> bool:
    """``geometry_msgs/Twist`` and ``geometry_msgs/msg/Twist`` name the same type."""
    return a.replace("/msg/", "/").replace("/srv/", "/") == b.replace("/msg/", "/").replace("/srv/", "/")


class _Rosapi:
    """The handlers, each reading the registry (or a node) at the time of the call."""

    def __init__(self, access: CoreAccess) -> None:
        self._access = access
        self._registry = access.registry

    def _graph(self) -> dict[str, Any]:
        return self._registry.graph()

    # -- topics ---------------------------------------------------------------------------------

    def topics(self, request: Any) -> rosapi.TopicsResponse:
        topics = self._graph()["topics"]
        return rosapi.TopicsResponse(topics=[t["name"] for t in topics], types=[t["type"] for t in topics])

    def topics_for_type(self, request: rosapi.TopicsForTypeRequest) -> rosapi.TopicsForTypeResponse:
        topics = [t["name"] for t in self._graph()["topics"] if _same_type(t["type"], request.type)]
        return rosapi.TopicsForTypeResponse(topics=topics)

    def topic_type(self, request: rosapi.TopicTypeRequest) -> rosapi.TopicTypeResponse:
        name = _absolute(request.topic)
        return rosapi.TopicTypeResponse(type=(self._registry.topic_type(name) or "") if name else "")

    def topics_and_raw_types(self, request: Any) -> rosapi.TopicsAndRawTypesResponse:
        """Every topic with its type and that type's whole definition (``rosbag2``'s text: the
        type's fields, then each type it uses after a line of ``=`` and ``MSG: pkg/Name``)."""
        topics = self._graph()["topics"]
        texts = []
        for topic in topics:
            cls = _lookup(topic["type"], Message)
            texts.append(definition_text(cls) if cls is not None else "")
        return rosapi.TopicsAndRawTypesResponse(
            topics=[t["name"] for t in topics], types=[t["type"] for t in topics], typedefs_full_text=texts
        )

    def publishers(self, request: rosapi.PublishersRequest) -> rosapi.PublishersResponse:
        name = _absolute(request.topic)
        return rosapi.PublishersResponse(publishers=[p.node for p in self._registry.publishers(name)] if name else [])

    def subscribers(self, request: rosapi.SubscribersRequest) -> rosapi.SubscribersResponse:
        name = _absolute(request.topic)
        return rosapi.SubscribersResponse(subscribers=self._registry.subscribers(name) if name else [])

    # -- services -------------------------------------------------------------------------------

    def services(self, request: Any) -> rosapi.ServicesResponse:
        return rosapi.ServicesResponse(services=[s["name"] for s in self._graph()["services"]])

    def services_for_type(self, request: rosapi.ServicesForTypeRequest) -> rosapi.ServicesForTypeResponse:
        services = [s["name"] for s in self._graph()["services"] if _same_type(s["type"], request.type)]
        return rosapi.ServicesForTypeResponse(services=services)

    def _service(self, name: str) -> dict[str, str] | None:
        absolute = _absolute(name)
        return next((s for s in self._graph()["services"] if s["name"] == absolute), None)

    def service_type(self, request: rosapi.ServiceTypeRequest) -> rosapi.ServiceTypeResponse:
        service = self._service(request.service)
        return rosapi.ServiceTypeResponse(type=service["type"] if service else "")

    def service_node(self, request: rosapi.ServiceNodeRequest) -> rosapi.ServiceNodeResponse:
        service = self._service(request.service)
        return rosapi.ServiceNodeResponse(node=service["node"] if service else "")

    def service_providers(self, request: rosapi.ServiceProvidersRequest) -> rosapi.ServiceProvidersResponse:
        service = self._service(request.service)
        return rosapi.ServiceProvidersResponse(providers=[service["node"]] if service else [])

    def service_host(self, request: rosapi.ServiceHostRequest) -> rosapi.ServiceHostResponse:
        """The host of the node serving a service (ROS 1's rosapi: the host of its URI)."""
        service = self._service(request.service)
        node = self._registry.nodes.get(service["node"]) if service else None
        host = urlsplit(node.description.url).hostname if node is not None and node.description.url else None
        return rosapi.ServiceHostResponse(host=host or "")

    # -- actions --------------------------------------------------------------------------------

    def action_servers(self, request: Any) -> rosapi.GetActionServersResponse:
        """ROS 2's actions with a server, and ROS 1 actionlib's: a namespace with all five of
        ``goal``, ``cancel``, ``status``, ``feedback`` and ``result`` topics (ROS 1's rosapi's rule)."""
        graph = self._graph()
        names = set(actions_in_graph(graph))
        parts: dict[str, set[str]] = {}
        for topic in graph["topics"]:
            namespace, _, last = topic["name"].rpartition("/")
            if namespace:
                parts.setdefault(namespace, set()).add(last)
        names |= {namespace for namespace, found in parts.items() if found >= _ACTIONLIB_TOPICS}
        return rosapi.GetActionServersResponse(action_servers=sorted(names))

    def action_type(self, request: rosapi.ActionTypeRequest) -> rosapi.ActionTypeResponse:
        found = actions_in_graph(self._graph()).get(_absolute(request.action))
        return rosapi.ActionTypeResponse(type=found.type if found is not None else "")

    # -- nodes ----------------------------------------------------------------------------------

    def nodes(self, request: Any) -> rosapi.NodesResponse:
        return rosapi.NodesResponse(nodes=[n["name"] for n in self._graph()["nodes"]])

    def node_details(self, request: rosapi.NodeDetailsRequest) -> rosapi.NodeDetailsResponse:
        wanted = "/" + request.node.strip("/")
        node = next((n for n in self._graph()["nodes"] if n["name"] == wanted), None)
        if node is None:
            return rosapi.NodeDetailsResponse()
        return rosapi.NodeDetailsResponse(
            subscribing=node["subscriptions"], publishing=node["publications"], services=node["services"]
        )

    # -- types ----------------------------------------------------------------------------------

    def interfaces(self, request: Any) -> rosapi.InterfacesResponse:
        return rosapi.InterfacesResponse(interfaces=interface_names())

    def message_details(self, request: rosapi.MessageDetailsRequest) -> rosapi.MessageDetailsResponse:
        cls = _lookup(request.type, Message)
        return rosapi.MessageDetailsResponse(typedefs=typedefs(cls) if cls else [])

    def service_request_details(self, request: rosapi.ServiceRequestDetailsRequest) -> rosapi.ServiceRequestDetailsResponse:
        srv = _lookup(request.type, ServiceType)
        return rosapi.ServiceRequestDetailsResponse(typedefs=typedefs(srv.Request) if srv else [])

    def service_response_details(
        self, request: rosapi.ServiceResponseDetailsRequest
    ) -> rosapi.ServiceResponseDetailsResponse:
        srv = _lookup(request.type, ServiceType)
        return rosapi.ServiceResponseDetailsResponse(typedefs=typedefs(srv.Response) if srv else [])

    # -- time and version -----------------------------------------------------------------------

    async def get_time(self, request: Any) -> rosapi.GetTimeResponse:
        return rosapi.GetTimeResponse(time=await clock.current(self._access))

    def get_ros_version(self, request: Any) -> rosapi.GetROSVersionResponse:
        return rosapi.GetROSVersionResponse(version=2, distro=ROS_DISTRO)


def _lookup(name: str, kind: type) -> Any:
    try:
        found = get_interface(name)
    except UnknownInterfaceError:
        return None
    return found if isinstance(found, type) and issubclass(found, kind) else None

