"""The Foxglove endpoint with @foxglove/ws-protocol's FoxgloveClient (npm, run by Node), the
library Foxglove and Lichtblick are built on."""

from __future__ import annotations

import json

import pytest

from tests.conftest import wait_until
from tests.services.protocols.conftest import Bridge

pytestmark = pytest.mark.timeout(90)


@pytest.mark.parametrize("subprotocol", ["foxglove.websocket.v1", "foxglove.sdk.v1"])
async def test_foxglove_client_sees_typed_channels_reads_publishes_and_calls(bridge: Bridge, subprotocol: str) -> None:
    client = await bridge.client("foxglove_client.mjs", bridge.foxglove_url, "tour", subprotocol)
    info = (await client.expect("serverInfo"))["serverInfo"]
    assert {"clientPublish", "services", "parameters", "connectionGraph", "time"} <= set(info["capabilities"])
    assert info["supportedEncodings"] == ["json"] and info["metadata"]["ROS_DISTRO"] == "humble"

    channel = await client.expect("channel")
    pose = channel["channel"]
    assert pose["encoding"] == "json" and pose["schemaEncoding"] == "jsonschema"
    assert pose["schemaName"] == "geometry_msgs/msg/PoseStamped"
    schema = json.loads(pose["schema"])
    stamp = schema["properties"]["header"]["properties"]["stamp"]
    assert {"sec", "nanosec", "nsec"} <= set(stamp["properties"])  # Foxglove reads sec/nsec
    assert "/clock" in channel["topics"] and "/drone/name" in channel["topics"]

    service = (await client.expect("service"))["service"]
    assert service["type"] == "std_srvs/srv/Trigger"
    assert json.loads(service["response"]["schema"])["properties"]["success"] == {"type": "boolean"}

    received = await client.expect("message")
    message = received["message"]
    assert message["header"]["stamp"]["nsec"] == message["header"]["stamp"]["nanosec"]
    assert message["pose"]["position"] == {"x": 1.0, "y": 2.0, "z": 0.0}
    # On the sim clock: the drone's /clock says 100 s and more, and so do timestamps.
    assert received["timestamp"] >= 100 * 10**9
    assert (await client.expect("time"))["time"] >= 100 * 10**9
    assert (await client.expect("latched"))["latched"] == {"data": "iris"}

    await client.expect("published")
    await wait_until(lambda: [c.linear.x for c in bridge.drone.commands] == [3.0, 3.5], what="the teleop messages")
    assert (await client.expect("take_off"))["take_off"] == {
        "response": {"success": True, "message": "All ok!"},
        "encoding": "json",
    }
    failure = (await client.expect("bad_call"))["bad_call"]["failure"]
    assert "nonsense" in failure  # the request's bad field is named
    graph = (await client.expect("graph"))["graph"]
    published = {t["name"]: t["publisherIds"] for t in graph["publishedTopics"]}
    assert published["/drone/pose"] == ["/drone"]
    assert any(p.startswith("/foxglove_client_") for p in published["/drone/cmd_vel"])  # the client, as itself
    await client.finish()
