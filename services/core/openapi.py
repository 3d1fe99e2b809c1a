"""One OpenAPI document for the whole system: the core's own API plus every live node's
services and topics, so ``/docs`` is the one page where a user sees every command."""

from __future__ import annotations

import asyncio
import copy
from typing import Any

from services.core.core_node import CORE_NODE
from services.core.registry import NodeRecord, Registry
from services.runtime.http_client import HttpClient, HttpError
from services.runtime.parameter_service import is_parameter_service
from services.runtime.service_groups import SYSTEM_NODES, ServiceGroup, service_group

__all__ = ["aggregate_openapi"]

_FETCH_TIMEOUT_S = 1.5
_GATEWAY_RESPONSES = {
    "503": {"description": "The node hosting the service is not reachable"},
    "504": {"description": "The service did not answer in time (SKYDECK_GATEWAY_TIMEOUT_S)"},
}


_SHARED_TOPICS = "topics of several nodes"
"""The section of a topic more than one node publishes (every node's /rosout and /parameter_events)."""


async def aggregate_openapi(core_schema: dict[str, Any], registry: Registry, http: HttpClient) -> dict[str, Any]:
    """The core's schema extended with each live node's service and topic paths (tagged by node).

    Swagger UI shows sections in the order of the document's ``tags``: the world's nodes first
    (their commands and topics), then the topics several nodes publish, then each node's
    parameter services, then Skydeck's own nodes and the core's API (:mod:`service_groups`).
    """
    schema = copy.deepcopy(core_schema)
    core_paths: dict[str, Any] = schema.setdefault("paths", {})
    components: dict[str, Any] = schema.setdefault("components", {}).setdefault("schemas", {})
    records = [r for name, r in sorted(registry.nodes.items()) if name != CORE_NODE]  # its topics are its clients'
    node_schemas = await asyncio.gather(*(_fetch(http, record) for record in records))
    placed: dict[str, tuple[tuple[int, int], str, dict[str, Any]]] = {}  # path -> (rank, tag, item)
    publishers: dict[str, int] = {}
    for record, node_schema in zip(records, node_schemas, strict=True):
        if node_schema is None:
            continue
        node = record.description.name
        services = {e.name for e in record.description.services}
        topics = {e.name for e in record.description.publications}
        for path in topics:
            publishers[path] = publishers.get(path, 0) + 1
        for path, item in node_schema.get("paths", {}).items():
            if path not in services and path not in topics:
                continue
            if path in services:
                group = service_group(path, node)
            else:  # a topic: with its node's commands
                group = ServiceGroup.SYSTEM if node in SYSTEM_NODES else ServiceGroup.COMMAND
            tag = f"node {node}" + (" parameters" if is_parameter_service(node, path) else "")
            for method, operation in item.items():
                if method == "post":  # what the gateway itself may answer for a service call
                    operation.setdefault("responses", {}).update(_GATEWAY_RESPONSES)
                operation["operationId"] = f"{operation.get('operationId', path)}__{node.strip('/')}"
            placed.setdefault(path, ((group, 0), tag, item))
        components.update(node_schema.get("components", {}).get("schemas", {}))
    for path, count in publishers.items():  # after the world's nodes, under a name of its own
        if count > 1 and path in placed and placed[path][0][0] is ServiceGroup.COMMAND:
            placed[path] = ((ServiceGroup.COMMAND, 1), _SHARED_TOPICS, placed[path][2])
    # Within a section, paths keep the order their node gave them (sorted() is stable).
    ordered = sorted(placed.items(), key=lambda entry: (entry[1][0], entry[1][1]))
    paths: dict[str, Any] = {}
    tags: list[str] = []
    for path, (_, tag, item) in ordered:
        for operation in item.values():
            operation["tags"] = [tag]
        paths[path] = item
        tags.append(tag)
    for item in core_paths.values():  # the core's own API last, in its own order
        tags += [tag for operation in item.values() for tag in operation.get("tags", ())]
    schema["paths"] = {**paths, **core_paths}
    schema["tags"] = [{"name": tag} for tag in dict.fromkeys(tags)]
    return schema


async def _fetch(http: HttpClient, record: NodeRecord) -> dict[str, Any] | None:
    try:
        reply = await http.get(record.description.url.rstrip("/") + "/openapi.json", timeout_s=_FETCH_TIMEOUT_S)
        if reply.status != 200:
            return None
        return reply.json()  # type: ignore[no-any-return]
    except (HttpError, ValueError):
        return None  # a node that cannot answer now is left out of this page, not an error
