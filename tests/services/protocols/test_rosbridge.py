"""rosbridge v2 op by op, with a plain WebSocket: options, fragments, timeouts, bad input, the
token, and the client in the graph. (The real clients are in test_rosbridge_roslib*.py.)"""

from __future__ import annotations

import asyncio
import itertools
import json
from typing import Any

import httpx
import pytest
from websockets.asyncio.client import ClientConnection, connect

from tests.conftest import wait_until
from tests.services.cli.test_cli import skydeck
from tests.services.protocols.conftest import Bridge, stuck_node

pytestmark = pytest.mark.timeout(60)


async def send(websocket: ClientConnection, **op: Any) -> None:
    await websocket.send(json.dumps(op))


async def receive(websocket: ClientConnection, op: str | None = None, timeout_s: float = 10.0, **match: Any) -> dict[str, Any]:
    """The next message (of ``op``, with the fields in ``match``), skipping others."""
    async with asyncio.timeout(timeout_s):
        while True:
            message = json.loads(await websocket.recv())
            if (op is None or message["op"] == op) and all(message.get(k) == v for k, v in match.items()):
                return message  # type: ignore[no-any-return]


async def call(websocket: ClientConnection, service: str, call_id: str, **fields: Any) -> dict[str, Any]:
    await send(websocket, op="call_service", service=service, id=call_id, **fields)
    return await receive(websocket, "service_response", id=call_id)


async def test_subscribe_and_unsubscribe_by_id(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="subscribe", topic="/drone/pose", id="a", type="geometry_msgs/msg/PoseStamped")
        await send(ws, op="subscribe", topic="/drone/pose", id="b")
        message = await receive(ws, "publish")
        assert message["topic"] == "/drone/pose" and message["msg"]["header"]["frame_id"] == "map"
        await send(ws, op="unsubscribe", topic="/drone/pose", id="a")
        await receive(ws, "publish")  # "b" still reads
        await send(ws, op="unsubscribe", topic="/drone/pose", id="b")
        await wait_until(lambda: not _core_reads(bridge, "/drone/pose"), what="the core to stop reading")


def _core_reads(bridge: Bridge, topic: str) -> bool:
    endpoint = bridge.core.app.state.core_node.endpoint(topic)  # type: ignore[union-attr]
    return endpoint is not None and bool(endpoint.taps)


async def test_throttle_rate_and_queue_length(bridge: Bridge) -> None:
    # The drone publishes every 50 ms, each stamp one step (50 ms of its clock) after the last.
    step_ns = 50_000_000

    async def steps(ws: ClientConnection, count: int) -> list[int]:
        stamps = [(await receive(ws, "publish"))["msg"]["header"]["stamp"] for _ in range(count)]
        ns = [stamp["sec"] * 10**9 + stamp["nanosec"] for stamp in stamps]
        return [(b - a) // step_ns for a, b in itertools.pairwise(ns)]

    async with connect(bridge.rosbridge_url) as newest, connect(bridge.rosbridge_url) as queued:
        # Throttled with no queue (or a queue of 1): the newest message each period, others skipped.
        await send(newest, op="subscribe", topic="/drone/pose", throttle_rate=500, queue_length=1)
        # Throttled with a queue: every message, one per period, until the queue of 10 overflows.
        await send(queued, op="subscribe", topic="/drone/pose", throttle_rate=200, queue_length=10)
        assert all(step > 2 for step in await steps(newest, 2))
        assert await steps(queued, 4) == [1, 1, 1]


async def test_a_late_subscriber_gets_the_latched_message(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="subscribe", topic="/drone/name")
        assert (await receive(ws, "publish"))["msg"] == {"data": "iris"}
    # Latched by a rosbridge client that advertised with `latch` (roslibjs's and roslibpy's
    # Topic(latch=True)): published once, then read by a client that comes later.
    async with connect(bridge.rosbridge_url) as publisher:
        await send(publisher, op="advertise", topic="/demo/mode", type="std_msgs/msg/String", latch=True)
        await send(publisher, op="publish", topic="/demo/mode", msg={"data": "auto"})
        await send(publisher, op="advertise", topic="/demo/said", type="std_msgs/msg/String")  # not latched
        await send(publisher, op="publish", topic="/demo/said", msg={"data": "once"})
        await wait_until(lambda: bridge.core.registry.topic_type("/demo/said") is not None, what="the topics")
        async with connect(bridge.rosbridge_url) as late:
            await send(late, op="subscribe", topic="/demo/said")
            await send(late, op="subscribe", topic="/demo/mode")
            assert await receive(late, "publish") == {"op": "publish", "topic": "/demo/mode", "msg": {"data": "auto"}}
            await send(publisher, op="publish", topic="/demo/said", msg={"data": "twice"})
            assert (await receive(late, "publish"))["msg"] == {"data": "twice"}  # "once" never came


async def test_a_message_published_right_after_advertise_reaches_a_subscribed_node(bridge: Bridge) -> None:
    # The drone subscribes to /drone/cmd_vel and links to the core only once the core publishes
    # it; what the client sends in that moment waits for the link (roslibpy's actionlib goal).
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="advertise", topic="/drone/cmd_vel", type="geometry_msgs/msg/Twist")
        await send(ws, op="publish", topic="/drone/cmd_vel", msg={"linear": {"x": 1.0}})
        await send(ws, op="publish", topic="/drone/cmd_vel", msg={"linear": {"x": 2.0}})
        await wait_until(lambda: len(bridge.drone.commands) >= 2, what="the drone to get both commands")
        await send(ws, op="publish", topic="/drone/cmd_vel", msg={"linear": {"x": 3.0}})
        await wait_until(lambda: len(bridge.drone.commands) >= 3, what="the third command")
    assert [command.linear.x for command in bridge.drone.commands] == [1.0, 2.0, 3.0]  # each once, in order


async def test_fragments_both_ways(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="subscribe", topic="/drone/pose", fragment_size=50)
        pieces = [await receive(ws, "fragment")]
        while len(pieces) < pieces[0]["total"]:
            pieces.append(await receive(ws, "fragment", id=pieces[0]["id"]))
        whole = json.loads("".join(p["data"] for p in sorted(pieces, key=lambda p: p["num"])))
        assert whole["op"] == "publish" and whole["msg"]["header"]["frame_id"] == "map"
        # A client may fragment its own frames: a call_service in three pieces.
        text = json.dumps({"op": "call_service", "service": "/rosapi/topic_type", "id": "f", "args": {"topic": "/clock"}})
        third = len(text) // 3 + 1
        for num in range(3):
            await send(ws, op="fragment", id="x", data=text[num * third : (num + 1) * third], num=num, total=3)
        answer = await receive(ws, "service_response", id="f")
        assert answer["values"] == {"type": "builtin_interfaces/msg/Time"} and answer["result"] is True
        # A call's own fragment_size: its service_response comes in fragments.
        await send(ws, op="call_service", service="/rosapi/message_details", id="big", fragment_size=100,
                   args={"type": "geometry_msgs/msg/PoseStamped"})  # fmt: skip
        pieces = [await receive(ws, "fragment", id="/rosapi/message_details:1")]
        while len(pieces) < pieces[0]["total"]:
            pieces.append(await receive(ws, "fragment", id=pieces[0]["id"]))
        assert len(pieces) > 1 and all(len(p["data"]) <= 100 for p in pieces)
        response = json.loads("".join(p["data"] for p in sorted(pieces, key=lambda p: p["num"])))
        assert response["op"] == "service_response" and response["id"] == "big"
        assert response["values"]["typedefs"][0]["type"] == "geometry_msgs/msg/PoseStamped"


async def test_call_service_args_as_object_list_or_none(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        by_object = await call(ws, "/rosapi/topic_type", "1", args={"topic": "/drone/pose"})
        by_list = await call(ws, "rosapi/topic_type", "2", args=["/drone/pose"])
        empty = await call(ws, "/control/take_off", "3")
    assert by_object["values"] == by_list["values"] == {"type": "geometry_msgs/msg/PoseStamped"}
    assert by_list["service"] == "/rosapi/topic_type"
    assert empty == {"op": "service_response", "service": "/control/take_off", "id": "3", "values": {"success": True, "message": "All ok!"}, "result": True}


async def test_a_call_nobody_answers_ends_with_its_timeout(bridge: Bridge) -> None:
    async with stuck_node(bridge), connect(bridge.rosbridge_url) as ws:
        answer = await call(ws, "/stuck/wait", "t", timeout=0.3)
        assert answer["result"] is False and "did not answer within 0.3 s" in answer["values"]
        # A service hosted by a client that never answers ends the same way.
        await send(ws, op="advertise_service", service="/mute/trigger", type="std_srvs/srv/Trigger")
        await wait_until(lambda: bridge.core.registry.service("/mute/trigger") is not None, what="hosting")
        async with connect(bridge.rosbridge_url) as caller:
            answer = await call(caller, "/mute/trigger", "m", timeout=0.3)
        assert answer["result"] is False and "did not answer within 0.3 s" in answer["values"]
        forwarded = await receive(ws, "call_service")  # the host was asked, and never replied
        assert forwarded["service"] == "/mute/trigger" and forwarded["args"] == {}


async def test_a_call_with_no_timeout_ends_at_the_default_with_an_error_response(impatient_bridge: Bridge) -> None:
    bridge = impatient_bridge  # the core's gateway timeout (SKYDECK_GATEWAY_TIMEOUT_S) is 1 s here
    async with stuck_node(bridge), connect(bridge.rosbridge_url) as ws:
        answer = await call(ws, "/stuck/wait", "d")
        assert answer["result"] is False and "did not answer within 1 s" in answer["values"]
        await send(ws, op="advertise_service", service="/mute/trigger", type="std_srvs/srv/Trigger")
        await wait_until(lambda: bridge.core.registry.service("/mute/trigger") is not None, what="hosting")
        async with connect(bridge.rosbridge_url) as caller:
            answer = await call(caller, "/mute/trigger", "m")
            assert answer["result"] is False and "did not answer within 1 s" in answer["values"]
            # Both connections carry on.
            assert (await call(caller, "/control/take_off", "t"))["result"] is True
        assert (await call(ws, "rosapi/topic_type", "y", args={"topic": "/clock"}))["result"] is True


@pytest.mark.parametrize(
    ("frame", "fragment"),
    [
        ("{not json", "not JSON"),
        ("[1, 2]", 'JSON object with an "op"'),
        ('{"op": "teleport"}', "unknown op 'teleport'"),
        ('{"op": "subscribe", "id": "s1"}', "subscribe: topic: Field required"),
        ('{"op": "publish", "topic": "/drone/cmd_vel", "msg": {"linear": {"x": "fast"}}, "id": "p"}', "linear.x"),
        ('{"op": "publish", "topic": "/drone/cmd_vel", "msg": {"speed": 3}}', "speed"),
        ('{"op": "publish", "topic": "/nobody/knows", "msg": {}}', "has no type yet"),
        ('{"op": "advertise", "topic": "/drone/pose", "type": "std_msgs/msg/String"}', "is geometry_msgs/msg/PoseStamped"),
        ('{"op": "advertise", "topic": "/x", "type": "nope_msgs/msg/Nothing"}', "nope_msgs/msg/Nothing"),
        ('{"op": "subscribe", "topic": "/drone/pose", "compression": "zip"}', "subscribe: compression: Input should be 'none', 'png', 'cbor' or 'cbor-raw'"),
        ('{"op": "subscribe", "topic": "/not/yet"}', "/not/yet does not exist yet and no type was given"),
        ('{"op": "subscribe", "topic": "/api/graph"}', "reserved"),
        ('{"op": "set_level", "level": "loud"}', "level must be one of"),
        ('{"op": "service_response", "service": "/x", "id": "9", "values": {}}', "no call '9'"),
    ],
)
async def test_bad_input_gets_a_status_error_and_the_connection_carries_on(bridge: Bridge, frame: str, fragment: str) -> None:
    async with connect(bridge.rosbridge_url) as ws, connect(bridge.rosbridge_url) as bystander:
        await send(bystander, op="subscribe", topic="/drone/pose")
        await ws.send(frame)
        status = await receive(ws, "status")
        assert status["level"] == "error" and fragment in status["msg"], status
        if '"id"' in frame:
            assert status["id"] == json.loads(frame)["id"]
        await send(ws, op="subscribe", topic="/drone/pose")
        assert (await receive(ws, "publish"))["topic"] == "/drone/pose"  # still working
        assert (await receive(bystander, "publish"))["topic"] == "/drone/pose"  # and so is everyone else


async def test_binary_and_oversized_frames_get_a_status_error(bridge: Bridge) -> None:
    limit = bridge.core.settings.max_message_bytes
    async with connect(bridge.rosbridge_url, max_size=None) as ws:
        await ws.send(b"\x00\x01")
        assert "JSON text" in (await receive(ws, "status"))["msg"]
        await send(ws, op="publish", topic="/drone/cmd_vel", msg={"padding": "x" * limit})
        assert "over" in (await receive(ws, "status"))["msg"]
        await send(ws, op="call_service", service="/no/such", id="n")
        answer = json.loads(await asyncio.wait_for(ws.recv(), 10))  # the response, and no status first
        assert answer["op"] == "service_response" and answer["id"] == "n"
        assert answer["result"] is False and "no service /no/such" in answer["values"]


async def test_status_levels_are_what_the_client_asked_for(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="unadvertise", topic="/never/advertised")  # a warning: not sent by default
        await send(ws, op="set_level", level="warning")
        await send(ws, op="unadvertise", topic="/never/advertised", id="w")
        status = await receive(ws, "status")
        assert status == {"op": "status", "level": "warning", "msg": "/never/advertised was not advertised by this client", "id": "w"}
        await send(ws, op="set_level", level="none")
        await ws.send("{broken")
        await send(ws, op="subscribe", topic="/drone/name")
        assert (await receive(ws))["op"] == "publish"  # no status in between


async def test_the_write_token_is_needed_to_publish_call_and_host(locked_bridge: Bridge) -> None:
    bridge = locked_bridge
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="subscribe", topic="/drone/name")  # reading stays open
        assert (await receive(ws, "publish"))["msg"] == {"data": "iris"}
        await send(ws, op="publish", topic="/drone/cmd_vel", msg={}, id="p")
        assert "need the token" in (await receive(ws, "status", id="p"))["msg"]
        answer = await call(ws, "/control/take_off", "c")
        assert answer["result"] is False and "need the token" in answer["values"]
        await send(ws, op="advertise_service", service="/x/y", type="std_srvs/srv/Trigger", id="h")
        assert "need the token" in (await receive(ws, "status", id="h"))["msg"]
        await send(ws, op="auth", mac="wrong", id="a1")
        assert "not this core's token" in (await receive(ws, "status", id="a1"))["msg"]
        await send(ws, op="auth", mac="secret", client="", dest="", rand="", t=0, level="admin", end=0)
        assert (await call(ws, "/control/take_off", "c2"))["result"] is True
    async with connect(bridge.rosbridge_url + "/?token=secret") as ws:
        assert (await call(ws, "/control/take_off", "c3"))["values"]["success"] is False  # flying already
    assert bridge.drone.commands == []


async def test_clients_are_nodes_in_the_graph_and_node_list(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="subscribe", topic="/drone/pose")
        await send(ws, op="advertise", topic="/drone/cmd_vel", type="geometry_msgs/msg/Twist")
        await send(ws, op="advertise_service", service="/demo/ping", type="std_srvs/srv/Trigger")
        await receive(ws, "publish")
        await wait_until(lambda: bridge.core.registry.service("/demo/ping") is not None, what="the service")
        async with httpx.AsyncClient() as http:
            graph = (await http.get(bridge.core_url + "/api/graph")).json()
        client = next(n for n in graph["nodes"] if n["name"].startswith("/rosbridge_client_"))
        assert client["client"].startswith("rosbridge client 127.0.0.1:")
        assert client["subscriptions"] == ["/drone/pose"] and client["publications"] == ["/drone/cmd_vel"]
        assert client["services"] == ["/demo/ping"]
        assert {"name": "/demo/ping", "type": "std_srvs/srv/Trigger", "node": client["name"]} in graph["services"]
        code, out, _ = await skydeck(bridge.core_url, "node", "list")
        assert code == 0 and client["name"] in out.split() and "/rosapi" in out.split()
        code, out, _ = await skydeck(bridge.core_url, "node", "info", client["name"])
        assert code == 0 and "Client: rosbridge client 127.0.0.1:" in out and "/demo/ping [std_srvs/srv/Trigger]" in out
        # A node calls the client's service through the gateway, as it calls any other.
        forwarded = asyncio.create_task(receive(ws, "call_service"))
        async with httpx.AsyncClient() as http:
            reply = asyncio.create_task(http.post(bridge.core_url + "/demo/ping", json={}))
            request = await forwarded
            await send(ws, op="service_response", service="/demo/ping", id=request["id"], values={"success": True, "message": "pong"}, result=True)
            assert (await reply).json() == {"success": True, "message": "pong"}
    await wait_until(lambda: not any(n.startswith("/rosbridge_client_") for n in bridge.core.registry.nodes), what="the client to leave")
    assert bridge.core.registry.service("/demo/ping") is None
