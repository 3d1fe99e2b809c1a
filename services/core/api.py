"""The core's own API under ``/api``: the registry (graph, nodes, topics, services) and types."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Depends, HTTPException, Request
from pydantic import BaseModel

from services.core.registry import Registry
from services.runtime.wire import wire_description
from shared_models import (
    ActionType,
    Message,
    ServiceType,
    UnknownInterfaceError,
    get_interface,
    interface_names,
    interface_text,
)
from shared_models.definitions.loader import definitions_of

__all__ = ["router"]

router = APIRouter(prefix="/api", tags=["registry"])


class ErrorDetail(BaseModel):
    """Why a request was not answered, and what to do."""

    detail: str


def _not_found(what: str) -> dict[int | str, dict[str, Any]]:
    return {404: {"model": ErrorDetail, "description": f"No such {what}"}}


def _registry(request: Request) -> Registry:
    return request.app.state.registry  # type: ignore[no-any-return]


RegistryDep = Annotated[Registry, Depends(_registry)]


@router.get("/config")
async def config() -> dict[str, Any]:
    """What clients must agree on: close codes, stream limits, and each world's numbers and names."""
    from sim_server.worlds import worlds_config  # the table and descriptions only: no PyBullet

    return {**wire_description(), "worlds": worlds_config()}


@router.get("/graph")
async def graph(registry: RegistryDep) -> dict[str, Any]:
    """Nodes, topics (type, publishers, subscribers, rate) and services of the running system."""
    return registry.graph()


@router.get("/nodes/{name:path}", responses=_not_found("node"))
async def node_info(name: str, registry: RegistryDep) -> dict[str, Any]:
    """One node: URL, pid, publications, subscriptions and services (`rosnode info`)."""
    node_name = "/" + name.strip("/")
    for node in registry.graph()["nodes"]:
        if node["name"] == node_name:
            return node  # type: ignore[no-any-return]
    raise HTTPException(404, f"no node {node_name}: see `skydeck node list`")


@router.get("/topics/{name:path}", responses=_not_found("topic"))
async def topic_info(name: str, registry: RegistryDep) -> dict[str, Any]:
    """One topic: type, publishers, subscribers and rate (`rostopic info`)."""
    topic_name = "/" + name.strip("/")
    for topic in registry.graph()["topics"]:
        if topic["name"] == topic_name:
            return topic  # type: ignore[no-any-return]
    raise HTTPException(404, f"no topic {topic_name}: see `skydeck topic list`")


@router.get("/services/{name:path}", responses=_not_found("service"))
async def service_info(name: str, registry: RegistryDep) -> dict[str, Any]:
    """One service: type, hosting node and its URL (`rosservice info`)."""
    service_name = "/" + name.strip("/")
    found = registry.service(service_name)
    if found is None:
        raise HTTPException(404, f"no service {service_name}: see `skydeck service list`")
    entity, record = found
    return {"name": entity.name, "type": entity.type, "node": record.description.name, "url": record.description.url}


@router.get("/interfaces")
async def interfaces() -> dict[str, Any]:
    """Every message and service type the core knows (`ros2 interface list`)."""
    return {
        "interfaces": [
            {"name": name, "kind": name.split("/")[1]} for name in interface_names()
        ]
    }


@router.get("/interfaces/{name:path}", responses=_not_found("interface"))
async def interface(name: str) -> dict[str, Any]:
    """One type: its `interface show` text, JSON schema, default value, and the definition files
    of the types it needs that Skydeck does not ship (a node's own, by the type each declares)."""
    try:
        cls = get_interface(name)
    except UnknownInterfaceError as error:
        raise HTTPException(404, str(error)) from None
    definitions = definitions_of([cls])
    if isinstance(cls, type) and issubclass(cls, ActionType):
        parts = {"goal": cls.Goal, "result": cls.Result, "feedback": cls.Feedback}
        return {
            "name": cls.__ros_type__,
            "kind": "action",
            "text": interface_text(cls),
            "schema": {part: part_cls.model_json_schema() for part, part_cls in parts.items()},
            "default": {part: part_cls().model_dump(mode="json") for part, part_cls in parts.items()},
            "definitions": definitions,
        }
    if isinstance(cls, type) and issubclass(cls, ServiceType):
        return {
            "name": cls.__ros_type__,
            "kind": "srv",
            "text": interface_text(cls),
            "schema": {"request": cls.Request.model_json_schema(), "response": cls.Response.model_json_schema()},
            "default": {
                "request": cls.Request().model_dump(mode="json"),
                "response": cls.Response().model_dump(mode="json"),
            },
            "definitions": definitions,
        }
    message: type[Message] = cls
    return {
        "name": message.__ros_type__,
        "kind": "msg",
        "text": interface_text(message),
        "schema": message.model_json_schema(),
        "default": message().model_dump(mode="json"),
        "definitions": definitions,
    }
