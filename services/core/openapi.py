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

__all__ = ["aggregate_openapi"]

_FETCH_TIMEOUT_S = 1.5
_GATEWAY_RESPONSES = {
    "503": {"description": "The node hosting the service is not reachable"},
    "504": {"description": "The service did not answer in time (SKYDECK_GATEWAY_TIMEOUT_S)"},
}


async def aggregate_openapi(core_schema: dict[str, Any], registry: Registry, http: HttpClient) -> dict[str, Any]:
    """The core's schema extended with each live node's service and topic paths (tagged by node)."""
    schema = copy.deepcopy(core_schema)
    paths: dict[str, Any] = schema.setdefault("paths", {})
    components: dict[str, Any] = schema.setdefault("components", {}).setdefault("schemas", {})
    records = [r for name, r in sorted(registry.nodes.items()) if name != CORE_NODE]  # its topics are its clients'
    node_schemas = await asyncio.gather(*(_fetch(http, record) for record in records))
    for record, node_schema in zip(records, node_schemas, strict=True):
        if node_schema is None:
            continue
        description = record.description
        names = {e.name for e in description.services} | {e.name for e in description.publications}
        # A node's six parameter services get a section of their own, after its own services
        # (Swagger UI orders sections as their first path comes).
        node_paths = sorted(
            node_schema.get("paths", {}).items(), key=lambda entry: is_parameter_service(description.name, entry[0])
        )
        for path, item in node_paths:
            if path not in names:
                continue
            tag = f"node {description.name}" + (" parameters" if is_parameter_service(description.name, path) else "")
            for method, operation in item.items():
                operation["tags"] = [tag]
                if method == "post":  # what the gateway itself may answer for a service call
                    operation.setdefault("responses", {}).update(_GATEWAY_RESPONSES)
                operation["operationId"] = f"{operation.get('operationId', path)}__{description.name.strip('/')}"
            paths[path] = item
        components.update(node_schema.get("components", {}).get("schemas", {}))
    return schema


async def _fetch(http: HttpClient, record: NodeRecord) -> dict[str, Any] | None:
    try:
        reply = await http.get(record.description.url.rstrip("/") + "/openapi.json", timeout_s=_FETCH_TIMEOUT_S)
        if reply.status != 200:
            return None
        return reply.json()  # type: ignore[no-any-return]
    except (HttpError, ValueError):
        return None  # a node that cannot answer now is left out of this page, not an error
