"""The core's registry API, aggregated OpenAPI, docs page and reserved paths."""

from __future__ import annotations

import asyncio
import os

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from services.runtime import Node
from services.runtime.edge.links import stream_url
from services.runtime.protocol import RegisterFrame
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


async def test_docs_lead_with_the_world_s_nodes_then_parameters_then_the_core(core, start_node) -> None:
    await start_node(Sim)
    await start_node(Control)
    async with httpx.AsyncClient() as http:
        schema = (await http.get(core.url + "/openapi.json")).json()
    tags = [tag["name"] for tag in schema["tags"]]
    assert tags[:5] == [
        "node /sim",  # control has no commands or topics of its own: no section
        "topics of several nodes",  # /rosout and /parameter_events: every node's, not the first's
        "node /control parameters",
        "node /sim parameters",
        "registry",
    ], tags
    assert schema["paths"]["/rosout"]["get"]["tags"] == ["topics of several nodes"]
    assert schema["paths"]["/simulator/reset"]["post"]["tags"] == ["node /sim"]
    # the paths in the same order, so that any OpenAPI viewer shows them so
    first_tags = [next(iter(item.values()))["tags"][0] for item in schema["paths"].values()]
    assert list(dict.fromkeys(first_tags)) == tags


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


async def test_a_topic_posted_or_a_service_read_is_405_and_redoc_leads_to_docs(core, start_node) -> None:
    await start_node(Sim)
    async with httpx.AsyncClient() as http:
        posted = await http.post(core.url + "/drone/pose")
        read = await http.get(core.url + "/simulator/reset")
        redoc = await http.get(core.url + "/redoc", follow_redirects=False)
    assert posted.status_code == 405 and "is a topic" in posted.json()["detail"]
    assert read.status_code == 405 and "call it with POST" in read.json()["detail"]
    assert redoc.is_redirect and redoc.headers["location"] == "/docs"


async def test_a_newer_node_takes_the_name_and_the_older_is_told(core, start_node) -> None:
    older = await start_node(Sim)
    newer = await start_node(Sim)
    await wait_until(lambda: core.registry.nodes["/sim"].description.url == newer.url, what="the newer node's URL")
    assert older.url != newer.url
    await wait_until(lambda: older._stopping is not None and older._stopping.is_set(), what="the older node told to stop")


async def test_a_binary_session_frame_closes_that_session_with_1003(core, start_node) -> None:
    sim = await start_node(Sim)
    register = RegisterFrame(node=sim.describe()).model_dump_json()
    async with connect(stream_url(core.url, "/api/session")) as websocket:
        await websocket.send(register.replace('"name":"/sim"', '"name":"/other"'))
        await websocket.recv()  # registered
        await websocket.send(b"\x00\x01")
        with pytest.raises(ConnectionClosed) as closed:
            while True:
                await asyncio.wait_for(websocket.recv(), 5)
    assert closed.value.rcvd is not None and closed.value.rcvd.code == 1003
    assert "/sim" in core.registry.nodes  # nothing else disturbed
