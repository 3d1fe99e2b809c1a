"""The Foxglove protocol message by message, with a plain WebSocket: the handshake, binary
frames, bad input, the token and the graph. (FoxgloveClient itself: test_foxglove_client.py.)"""

from __future__ import annotations

import asyncio
import json
import struct
from typing import Any

import httpx
import pytest
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosed
from websockets.typing import Subprotocol

from tests.conftest import wait_until
from tests.services.cli.test_cli import skydeck
from tests.services.protocols.conftest import Bridge, stuck_node

pytestmark = pytest.mark.timeout(60)

V1 = [Subprotocol("foxglove.websocket.v1")]


async def receive(ws: ClientConnection, op: str, timeout_s: float = 10.0) -> dict[str, Any]:
    """The next JSON message of ``op`` (binary frames and other ops are skipped)."""
    async with asyncio.timeout(timeout_s):
        while True:
            message = await ws.recv()
            if isinstance(message, str) and (parsed := json.loads(message))["op"] == op:
                return parsed  # type: ignore[no-any-return]


async def binary(ws: ClientConnection, opcode: int, timeout_s: float = 10.0) -> bytes:
    async with asyncio.timeout(timeout_s):
        while True:
            message = await ws.recv()
            if isinstance(message, bytes) and message[0] == opcode:
                return message


async def channels(ws: ClientConnection) -> dict[str, int]:
    advertised = await receive(ws, "advertise")
    return {c["topic"]: c["id"] for c in advertised["channels"]}


async def send(ws: ClientConnection, **message: Any) -> None:
    await ws.send(json.dumps(message))


async def test_without_the_subprotocol_the_connection_is_refused_with_a_reason(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url) as ws:
        with pytest.raises(ConnectionClosed) as closed:
            await ws.recv()
    assert closed.value.rcvd is not None and closed.value.rcvd.code == 1008
    assert "foxglove.websocket.v1" in closed.value.rcvd.reason


async def test_message_frames_carry_the_subscription_the_time_and_the_payload(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1) as ws:
        assert ws.subprotocol == "foxglove.websocket.v1"
        info = await receive(ws, "serverInfo")
        assert "time" in info["capabilities"]
        ids = await channels(ws)
        await send(ws, op="subscribe", subscriptions=[{"id": 7, "channelId": ids["/drone/pose"]}])
        frame = await binary(ws, 0x01)
        sub_id, stamp_ns = struct.unpack_from("<IQ", frame, 1)
        payload = json.loads(frame[13:])
        assert sub_id == 7 and stamp_ns >= 100 * 10**9
        assert payload["header"]["stamp"]["nsec"] == payload["header"]["stamp"]["nanosec"]
        time_frame = await binary(ws, 0x02)
        assert struct.unpack_from("<Q", time_frame, 1)[0] >= 100 * 10**9
        await send(ws, op="unsubscribe", subscriptionIds=[7])
        await wait_until(lambda: not _core_reads(bridge, "/drone/pose"), what="the core to stop reading")


def _core_reads(bridge: Bridge, topic: str) -> bool:
    endpoint = bridge.core.app.state.core_node.endpoint(topic)  # type: ignore[union-attr]
    return endpoint is not None and bool(endpoint.taps)


async def test_two_clients_get_the_same_payload_made_once(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1) as a, connect(bridge.foxglove_url, subprotocols=V1) as b:
        for ws, sub_id in ((a, 1), (b, 2)):
            ids = await channels(ws)
            await send(ws, op="subscribe", subscriptions=[{"id": sub_id, "channelId": ids["/drone/pose"]}])
        frames_a = [await binary(a, 0x01) for _ in range(3)]
        frames_b = [await binary(b, 0x01) for _ in range(3)]
    payloads_a = {f[13:] for f in frames_a}
    assert payloads_a & {f[13:] for f in frames_b}  # the same bytes reached both
    assert {struct.unpack_from("<I", f, 1)[0] for f in frames_b} == {2}


async def test_the_advertised_channels_follow_the_graph(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1) as ws:
        ids = await channels(ws)
        assert "/demo/later" not in ids
        async with connect(bridge.rosbridge_url) as rosbridge:
            await rosbridge.send(json.dumps({"op": "advertise", "topic": "/demo/later", "type": "std_msgs/msg/Int32"}))
            added = (await receive(ws, "advertise"))["channels"]
            assert [(c["topic"], c["schemaName"]) for c in added] == [("/demo/later", "std_msgs/msg/Int32")]
        removed = await receive(ws, "unadvertise", timeout_s=15)  # after the core's linger
        assert removed["channelIds"] == [added[0]["id"]]


@pytest.mark.parametrize(
    ("message", "fragment"),
    [
        ("{nope", "not JSON"),
        ('"just a string"', 'JSON object with an "op"'),
        ('{"op": "fly"}', "unknown op 'fly'"),
        ('{"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 99999}]}', "no channel 99999"),
        ('{"op": "subscribe", "subscriptions": [{"id": -1, "channelId": 1}]}', "subscribe: subscriptions.0.id: Input should be greater than or equal to 0"),
        ('{"op": "subscribe"}', "subscribe: subscriptions: Field required"),
        ('{"op": "unsubscribe", "subscriptionIds": [42]}', "no subscription [42]"),
        ('{"op": "advertise", "channels": [{"id": 1, "topic": "/drone/cmd_vel", "encoding": "cbor", "schemaName": "geometry_msgs/msg/Twist"}]}', "encoding 'cbor'"),
        ('{"op": "advertise", "channels": [{"id": 1, "topic": "/drone/pose", "encoding": "json", "schemaName": "std_msgs/msg/String"}]}', "is geometry_msgs/msg/PoseStamped"),
        ('{"op": "fetchAsset", "uri": "package://x", "requestId": 1}', "unknown op 'fetchAsset'"),
    ],
)
async def test_bad_json_messages_get_a_status_and_the_connection_carries_on(bridge: Bridge, message: str, fragment: str) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1) as ws, connect(bridge.foxglove_url, subprotocols=V1) as bystander:
        ids = await channels(ws)
        await send(bystander, op="subscribe", subscriptions=[{"id": 9, "channelId": (await channels(bystander))["/drone/pose"]}])
        await ws.send(message)
        status = await receive(ws, "status")
        assert status["level"] == 2 and fragment in status["message"], status
        await send(ws, op="subscribe", subscriptions=[{"id": 5, "channelId": ids["/drone/pose"]}])
        assert struct.unpack_from("<I", await binary(ws, 0x01), 1)[0] == 5  # still working
        assert struct.unpack_from("<I", await binary(bystander, 0x01), 1)[0] == 9  # and so is everyone else


async def test_bad_binary_messages_get_a_status(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1, max_size=None) as ws:
        await receive(ws, "serverInfo")
        await ws.send(b"\x09abc")
        assert "binary opcode 0x09" in (await receive(ws, "status"))["message"]
        await ws.send(struct.pack("<BI", 1, 77) + b"{}")
        assert "no client channel 77" in (await receive(ws, "status"))["message"]
        await send(ws, op="advertise", channels=[{"id": 3, "topic": "/drone/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/msg/Twist"}])
        await ws.send(struct.pack("<BI", 1, 3) + b'{"linear": {"x": "fast"}}')
        assert "linear.x" in (await receive(ws, "status"))["message"]
        await ws.send(struct.pack("<BI", 1, 3) + b"\xff\xfe")
        assert "not JSON text" in (await receive(ws, "status"))["message"]
        await ws.send(struct.pack("<BIII", 2, 4242, 1, 4) + b"json{}")
        assert "no service 4242" in (await receive(ws, "status"))["message"]
        limit = bridge.core.settings.max_message_bytes
        await ws.send(struct.pack("<BI", 1, 3) + b" " * (limit + 1))
        assert f"over {limit} bytes" in (await receive(ws, "status"))["message"]
        await ws.send(struct.pack("<BI", 1, 3) + b'{"linear": {"x": 0.25}}')
        await wait_until(lambda: [c.linear.x for c in bridge.drone.commands] == [0.25], what="the good message")


async def test_service_calls_answer_or_fail_for_that_call_only(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1) as ws:
        services = {s["name"]: s["id"] for s in (await receive(ws, "advertiseServices"))["services"]}
        take_off = services["/control/take_off"]
        await ws.send(struct.pack("<BIII", 2, take_off, 11, 4) + b"json" + b"{}")
        answer = await binary(ws, 0x03)
        service_id, call_id, length = struct.unpack_from("<III", answer, 1)
        assert (service_id, call_id, answer[13 : 13 + length]) == (take_off, 11, b"json")
        assert json.loads(answer[13 + length :]) == {"success": True, "message": "All ok!"}
        await ws.send(struct.pack("<BIII", 2, take_off, 12, 4) + b"cbor" + b"\xa0")
        failure = await receive(ws, "serviceCallFailure")
        assert failure["callId"] == 12 and "encoding 'cbor'" in failure["message"]


async def test_the_write_token_guards_publishing_and_calls(locked_bridge: Bridge) -> None:
    bridge = locked_bridge
    async with connect(bridge.foxglove_url, subprotocols=V1) as ws:
        services = {s["name"]: s["id"] for s in (await receive(ws, "advertiseServices"))["services"]}
        await send(ws, op="advertise", channels=[{"id": 1, "topic": "/drone/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/msg/Twist"}])
        assert "need the token" in (await receive(ws, "status"))["message"]
        await ws.send(struct.pack("<BIII", 2, services["/control/take_off"], 1, 4) + b"json{}")
        assert "need the token" in (await receive(ws, "serviceCallFailure"))["message"]
        await send(ws, op="setParameters", parameters=[{"name": "/drone.speed", "value": 1.0}], id="p")
        assert "need the token" in (await receive(ws, "status"))["message"]
    async with connect(bridge.foxglove_url + "/?token=secret", subprotocols=V1) as ws:
        await send(ws, op="advertise", channels=[{"id": 1, "topic": "/drone/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/msg/Twist"}])
        await ws.send(struct.pack("<BI", 1, 1) + b'{"angular": {"z": 0.5}}')
        await wait_until(lambda: [c.angular.z for c in bridge.drone.commands] == [0.5], what="the message")


async def test_connection_graph_updates_follow_changes(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1) as ws:
        await send(ws, op="subscribeConnectionGraph")
        first = await receive(ws, "connectionGraphUpdate")
        published = {t["name"]: t["publisherIds"] for t in first["publishedTopics"]}
        assert published["/drone/pose"] == ["/drone"]
        assert {"name": "/control/take_off", "providerIds": ["/drone"]} in first["advertisedServices"]
        async with connect(bridge.rosbridge_url) as rosbridge:
            await rosbridge.send(json.dumps({"op": "advertise_service", "service": "/demo/flash", "type": "std_srvs/srv/Trigger"}))
            while True:
                update = await receive(ws, "connectionGraphUpdate")
                provided = {s["name"]: s["providerIds"] for s in update["advertisedServices"]}
                if "/demo/flash" in provided:
                    break
            assert provided["/demo/flash"][0].startswith("/rosbridge_client_")
        while "/demo/flash" not in (await receive(ws, "connectionGraphUpdate"))["removedServices"]:
            pass


async def test_a_foxglove_client_is_a_node_in_the_graph_and_node_list(bridge: Bridge) -> None:
    async with connect(bridge.foxglove_url, subprotocols=V1) as ws:
        ids = await channels(ws)
        await send(ws, op="subscribe", subscriptions=[{"id": 1, "channelId": ids["/drone/pose"]}])
        await send(ws, op="advertise", channels=[{"id": 2, "topic": "/drone/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/msg/Twist"}])
        await binary(ws, 0x01)
        await wait_until(lambda: any(n.startswith("/foxglove_client_") for n in _publishers(bridge, "/drone/cmd_vel")), what="the publication")
        async with httpx.AsyncClient() as http:
            graph = (await http.get(bridge.core_url + "/api/graph")).json()
        client = next(n for n in graph["nodes"] if n["name"].startswith("/foxglove_client_"))
        assert client["client"].startswith("foxglove client 127.0.0.1:")
        assert set(client["subscriptions"]) == {"/drone/pose", "/clock"}  # /clock: the server's time
        assert client["publications"] == ["/drone/cmd_vel"]
        code, out, _ = await skydeck(bridge.core_url, "node", "list")
        assert code == 0 and client["name"] in out.split()
        code, out, _ = await skydeck(bridge.core_url, "node", "info", client["name"])
        assert code == 0 and "Client: foxglove client 127.0.0.1:" in out and "/drone/cmd_vel" in out
    await wait_until(lambda: not any(n.startswith("/foxglove_client_") for n in bridge.core.registry.nodes), what="the client to leave")


def _publishers(bridge: Bridge, topic: str) -> list[str]:
    return [publisher.node for publisher in bridge.core.registry.publishers(topic)]


async def test_a_call_that_is_never_answered_fails_at_the_default_timeout(impatient_bridge: Bridge) -> None:
    bridge = impatient_bridge  # the core's default call timeout is 1 s here
    async with stuck_node(bridge), connect(bridge.foxglove_url, subprotocols=V1) as ws:
        services: dict[str, int] = {}
        while "/stuck/wait" not in services:
            services |= {s["name"]: s["id"] for s in (await receive(ws, "advertiseServices"))["services"]}
        await ws.send(struct.pack("<BIII", 2, services["/stuck/wait"], 5, 4) + b"json{}")
        failure = await receive(ws, "serviceCallFailure")
        assert failure["callId"] == 5 and "did not answer within 1 s" in failure["message"]
        await ws.send(struct.pack("<BIII", 2, services["/control/take_off"], 6, 4) + b"json{}")
        assert struct.unpack_from("<III", await binary(ws, 0x03), 1)[1] == 6  # the connection carries on
