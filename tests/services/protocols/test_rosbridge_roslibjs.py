"""rosbridge with roslibjs, the browser library most robot web apps use (npm ``roslib``, run by
Node from tests/clients)."""

from __future__ import annotations

import pytest

from tests.conftest import wait_until
from tests.services.protocols.conftest import Bridge

pytestmark = pytest.mark.timeout(90)


@pytest.mark.parametrize("where", ["port", "core"])
async def test_roslibjs_reads_publishes_calls_and_describes_types(bridge: Bridge, where: str) -> None:
    # The endpoint on its own port, and the same one at /rosbridge on the core's port.
    url = bridge.rosbridge_url if where == "port" else bridge.core_url.replace("http", "ws") + "/rosbridge"
    client = await bridge.client("roslibjs_client.mjs", url, "tour")
    assert (await client.line())["connected"] is True
    pose = (await client.expect("pose"))["pose"]
    assert pose["header"]["stamp"]["sec"] >= 100 and pose["pose"]["position"]["x"] == 1.0
    assert (await client.expect("latched"))["latched"] == {"data": "iris"}
    await client.expect("published")
    await wait_until(lambda: [c.linear.x for c in bridge.drone.commands] == [2.0, 2.5], what="both cmd_vel messages")
    assert (await client.expect("take_off"))["take_off"] == {"response": {"success": True, "message": "All ok!"}}
    topics = (await client.expect("topics"))["topics"]
    assert "/drone/pose" in topics["topics"]
    assert topics["types"][topics["topics"].index("/drone/pose")] == "geometry_msgs/msg/PoseStamped"
    typedefs = (await client.expect("typedefs"))["typedefs"]
    first = typedefs[0]
    assert first["type"] == "geometry_msgs/msg/PoseStamped"
    assert first["fieldnames"] == ["header", "pose"] and first["fieldarraylen"] == [-1, -1]
    assert {t["type"] for t in typedefs} >= {"std_msgs/msg/Header", "builtin_interfaces/msg/Time", "geometry_msgs/msg/Point"}
    missing = (await client.expect("missing"))["missing"]
    assert "no service /no/such/service" in missing["error"]
    await client.finish()


async def test_a_service_hosted_by_roslibjs_is_called_by_another_rosbridge_client(bridge: Bridge) -> None:
    client = await bridge.client("roslibjs_client.mjs", bridge.rosbridge_url, "host")
    await client.expect("advertised")
    called = (await client.expect("called"))["called"]
    assert called == {"response": {"success": True, "message": "from roslibjs"}}
    await client.finish()
