"""rospy's questions to the graph (``rospy.get_published_topics``), answered by the core's."""

from __future__ import annotations

from typing import Any

from services.ros.bridge import bridge
from services.ros.rospy.core import process

__all__ = ["get_published_topics", "graph_topic"]


def _graph() -> dict[str, Any]:
    node = process.require_node("asking the graph")

    async def fetch() -> dict[str, Any]:
        reply = await node.http.get(f"{node.settings.core_url.rstrip('/')}/api/graph", timeout_s=5.0)
        return reply.json() if reply.status == 200 else {}  # type: ignore[no-any-return]

    return bridge.run(fetch())


def graph_topic(name: str) -> dict[str, Any]:
    """What the core's graph says of topic ``name`` (its publishers, subscribers, type)."""
    return next((t for t in _graph().get("topics", []) if t.get("name") == name), {})


def get_published_topics(namespace: str = "/") -> list[list[str]]:
    """``[[topic, type], ...]`` of the topics with a publisher, under ``namespace``."""
    prefix = namespace.rstrip("/") + "/"
    return [
        [topic["name"], str(topic["type"]).replace("/msg/", "/")]
        for topic in _graph().get("topics", [])
        if topic.get("publishers") and topic["name"].startswith(prefix)
    ]
