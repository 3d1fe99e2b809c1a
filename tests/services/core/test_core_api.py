"""The core's registry API, aggregated OpenAPI, docs page and reserved paths."""

from __future__ import annotations

import os

import httpx

from services.runtime import Node
from shared_models.geometry_msgs import PoseStamped
from shared_models.std_srvs import Trigger, TriggerResponse
from tests.conftest import wait_until


class Sim(Node):
    def __init__(self, settings) -> None:
        super().__init__("sim", settings=settings)
        self.pose = self.create_publisher(PoseStamped, "/drone/pose", 10)
        self.create_service(Trigger, "/simulator/reset", lambda request: TriggerResponse(success=True))


class Control(Node):
    def __init__(self, settings) -> None:
        super().__init__("control", settings=settings)
        self.create_subscription(PoseStamped, "/drone/pose", lambda m: None, 10)


async def test_graph_lists_nodes_topics_services_with_pids(core, start_node) -> None:
    await start_node(Sim)
    await start_node(Control)
    async with httpx.AsyncClient() as http:
        graph = (await http.get(core.url + "/api/graph")).json()
    nodes = {n["name"]: n for n in graph["nodes"]}
    assert nodes["/sim"]["pid"] == os.getpid() and nodes["/sim"]["url"].startswith("http://127.0.0.1:")
    pose = next(t for t in graph["topics"] if t["name"] == "/drone/pose")
    assert pose["type"] == "geometry_msgs/msg/PoseStamped"
    assert pose["publishers"] == ["/sim"] and pose["subscribers"] == ["/control"]
    assert {"name": "/simulator/reset", "type": "std_srvs/srv/Trigger", "node": "/sim"} in graph["services"]


async def test_node_leaves_graph_when_it_stops(core, start_node) -> None:
    sim = await start_node(Sim)
    await sim.stop()
    await wait_until(lambda: "/sim" not in core.registry.nodes, what="the node to leave")


async def test_topic_rates_come_from_publisher_stats(core, start_node) -> None:
    sim = await start_node(Sim)
    sim.pose.publish(PoseStamped())
    await wait_until(
        lambda: any(t["rate_hz"] is not None for t in core.registry.graph()["topics"] if t["name"] == "/drone/pose"),
        timeout_s=5,
        what="a rate for /drone/pose",
    )


async def test_openapi_documents_every_live_service(core, start_node) -> None:
    await start_node(Sim)
    async with httpx.AsyncClient() as http:
        schema = (await http.get(core.url + "/openapi.json")).json()
        docs = await http.get(core.url + "/docs")
    operation = schema["paths"]["/simulator/reset"]["post"]
    assert operation["tags"] == ["node /sim"]
    assert "TriggerResponse" in str(operation["responses"]["200"])
    assert "/api/graph" in schema["paths"]
    assert docs.status_code == 200 and "/static/vendor/swagger-ui/swagger-ui-bundle.js" in docs.text
    assert "cdn" not in docs.text.lower()


async def test_interfaces_api(core) -> None:
    async with httpx.AsyncClient() as http:
        listing = (await http.get(core.url + "/api/interfaces")).json()
        twist = (await http.get(core.url + "/api/interfaces/geometry_msgs/msg/Twist")).json()
        unknown = await http.get(core.url + "/api/interfaces/geometry_msgs/msg/Twizt")
    assert {"name": "std_srvs/srv/Trigger", "kind": "srv"} in listing["interfaces"]
    assert twist["default"]["linear"] == {"x": 0.0, "y": 0.0, "z": 0.0}
    assert "Vector3 linear" in twist["text"]
    assert unknown.status_code == 404 and "Twist" in unknown.json()["detail"]


async def test_unknown_names_and_reserved_paths(core) -> None:
    async with httpx.AsyncClient() as http:
        unknown = await http.get(core.url + "/no/such/topic")
        bad = await http.get(core.url + "/bad//name")
        health = await http.get(core.url + "/health")
        big = await http.post(core.url + "/x", content=b"x" * (core.settings.max_message_bytes + 1))
    assert unknown.status_code == 404 and "skydeck topic list" in unknown.json()["detail"]
    assert bad.status_code == 404 and "invalid name" in bad.json()["detail"]
    assert health.json()["status"] == "ok"
    assert big.status_code == 413
