"""rosbridge with roslibpy, the Python client users have (PyPI, pinned in requirements.lock)."""

from __future__ import annotations

import asyncio

import pytest

from tests.conftest import wait_until
from tests.services.protocols.conftest import Bridge, Tuned, stuck_node

pytestmark = pytest.mark.timeout(90)


async def test_roslibpy_reads_publishes_calls_and_lists(bridge: Bridge) -> None:
    client = await bridge.client("roslibpy_client.py", bridge.rosbridge_url, "tour")
    assert (await client.line())["connected"] is True
    pose = (await client.expect("pose"))["pose"]
    assert pose["header"]["frame_id"] == "map" and pose["pose"]["position"]["y"] == 2.0
    assert (await client.expect("latched"))["latched"] == {"data": "iris"}  # a late subscriber gets it
    await client.expect("published")
    await wait_until(lambda: len(bridge.drone.commands) == 3, what="the three cmd_vel messages")
    assert [c.linear.x for c in bridge.drone.commands] == [0.5, 1.0, 1.5]
    assert (await client.expect("take_off"))["take_off"] == {"success": True, "message": "All ok!"}
    assert (await client.expect("again"))["again"]["success"] is False  # a refusal is an answer
    topics = (await client.expect("topics"))["topics"]
    assert {"/drone/pose", "/drone/cmd_vel", "/drone/name"} <= set(topics)
    assert (await client.expect("topic_type"))["topic_type"] == "geometry_msgs/msg/PoseStamped"
    assert {"/control/take_off", "/rosapi/topics"} <= set((await client.expect("services"))["services"])
    nodes = (await client.expect("nodes"))["nodes"]
    assert {"/drone", "/rosapi", "/skydeck_core"} <= set(nodes)
    assert any(name.startswith("/rosbridge_client_") for name in nodes)  # the client itself
    relative = (await client.expect("relative"))["relative"]
    assert relative["topics"] == topics and relative["types"][topics.index("/drone/pose")] == (
        "geometry_msgs/msg/PoseStamped"
    )
    assert (await client.expect("time"))["time"]["secs"] >= 100  # /clock's time, ROS 1 names
    assert "no service /no/such/service" in (await client.expect("missing"))["missing"]
    _no_traceback(await client.finish())


def _no_traceback(stderr: str) -> None:
    """roslibpy printed nothing of its own: a failed call is a service_response with result false,
    as rosbridge_suite sends it, and no `status` op (roslibpy has no handler for one, issue 32)."""
    assert "Traceback" not in stderr and "No handler registered" not in stderr, stderr


async def test_a_service_hosted_by_roslibpy_is_called_with_curl_through_the_core(bridge: Bridge) -> None:
    client = await bridge.client("roslibpy_client.py", bridge.rosbridge_url, "hosted")
    await client.expect("advertised")
    service = bridge.core.registry.service("/demo/set_light")
    assert service is not None and service[1].description.name.startswith("/rosbridge_client_")
    curl = await asyncio.create_subprocess_exec(
        "curl", "-sS", "-X", "POST", "-H", "content-type: application/json", "-d", '{"data": true}',
        bridge.core_url + "/demo/set_light", stdout=asyncio.subprocess.PIPE,
    )  # fmt: skip
    out, _ = await asyncio.wait_for(curl.communicate(), 20)
    assert out.decode() == '{"success":true,"message":"light on"}'
    assert (await client.expect("served"))["served"] == {"data": True}
    await client.go_on()
    assert (await client.expect("calls"))["calls"] == 1
    await client.finish()
    await wait_until(lambda: bridge.core.registry.service("/demo/set_light") is None, what="the service to go")


async def test_every_rosapi_service_answers_with_and_without_the_leading_slash(bridge: Bridge, tuned: Tuned) -> None:
    client = await bridge.client("roslibpy_client.py", bridge.rosbridge_url, "rosapi")
    assert (await client.line())["connected"] is True
    answers = {}
    for _ in range(14):
        line = await client.expect("rosapi")
        answers[line["rosapi"]] = line
    for name, line in answers.items():
        if name not in ("get_time", "set_param"):  # the time moves on; set twice: same answer
            assert line["slash"] == line["relative"], name
    topics = answers["topics"]["slash"]
    assert topics["types"][topics["topics"].index("/drone/pose")] == "geometry_msgs/msg/PoseStamped"
    assert answers["topics_for_type"]["slash"]["topics"] == ["/drone/pose"]
    assert {"/control/take_off", "/rosapi/get_time", "/tuned/get_parameters"} <= set(answers["services"]["slash"]["services"])
    assert answers["service_type"]["slash"]["type"] == "std_srvs/srv/Trigger"
    assert answers["topic_type"]["relative"]["type"] == "geometry_msgs/msg/PoseStamped"
    assert {"/drone", "/tuned", "/rosapi"} <= set(answers["nodes"]["slash"]["nodes"])
    drone = answers["node_details"]["relative"]
    assert "/drone/pose" in drone["publishing"] and "/drone/cmd_vel" in drone["subscribing"]
    assert "/control/take_off" in drone["services"]
    assert answers["message_details"]["relative"]["typedefs"][0]["type"] == "geometry_msgs/msg/PoseStamped"
    request = answers["service_request_details"]["relative"]["typedefs"][0]
    assert (request["fieldnames"], request["fieldtypes"]) == (["data"], ["bool"])
    response = answers["service_response_details"]["relative"]["typedefs"][0]
    assert response["fieldnames"] == ["success", "message"]
    assert answers["get_param"]["slash"] == {"value": "2.5", "successful": True, "reason": ""}
    assert answers["set_param"]["slash"]["successful"] is answers["set_param"]["relative"]["successful"] is True
    assert tuned.values["retries"] == 5
    assert "/tuned:max_speed" in answers["get_param_names"]["relative"]["names"]
    for spelling in ("slash", "relative"):  # ROS 1's secs/nsecs and ROS 2's sec/nanosec, the same time
        now = answers["get_time"][spelling]["time"]
        assert now["secs"] == now["sec"] >= 100 and now["nsecs"] == now["nanosec"]
    helpers = (await client.expect("helpers"))["helpers"]  # roslibpy's own methods, on the same services
    assert helpers["topics_for_type"] == ["/drone/pose"] and helpers["service_type"] == "std_srvs/srv/Trigger"
    assert "/drone/pose" in helpers["node_details"]["publishing"]
    assert "/tuned:retries" in helpers["params"] and helpers["param"] == 5
    assert helpers["request_details"]["typedefs"][0]["fieldnames"] == ["data"]
    await client.finish()


async def test_roslibpy_calling_a_service_that_never_answers_gets_an_error_at_the_default_timeout(
    impatient_bridge: Bridge,
) -> None:
    bridge = impatient_bridge  # the core's default call timeout (SKYDECK_GATEWAY_TIMEOUT_S) is 1 s here
    async with stuck_node(bridge):
        client = await bridge.client("roslibpy_client.py", bridge.rosbridge_url, "stuck")
        line = await client.expect("stuck")
        assert line["kind"] == "ServiceException" and "did not answer within 1 s" in line["stuck"]
        assert (await client.expect("after"))["after"] == "geometry_msgs/msg/PoseStamped"
        _no_traceback(await client.finish())


async def test_roslibpys_param_reads_ros1_parameters_as_rosapi_on_ros1_answers(bridge: Bridge) -> None:
    """An unset parameter is None (rosapi's JSON null: roslibpy parses it), a namespace a dict."""
    client = await bridge.client("roslibpy_client.py", bridge.rosbridge_url, "params")
    assert (await client.line())["connected"] is True
    assert (await client.expect("unset"))["unset"] is None
    assert (await client.expect("set"))["set"] == 1.5
    assert (await client.expect("namespace"))["namespace"] == {"max_speed": 1.5, "name": "neato"}
    assert (await client.expect("names"))["names"] == ["/robot/max_speed", "/robot/name"]
    assert (await client.expect("deleted"))["deleted"] is None
    assert "Traceback" not in await client.finish()


async def test_one_roslibpy_connection_hears_what_it_publishes(bridge: Bridge) -> None:
    client = await bridge.client("roslibpy_client.py", bridge.rosbridge_url, "echo")
    assert (await client.line())["connected"] is True
    assert (await client.expect("heard"))["heard"] == ["hello 0", "hello 1", "hello 2"]
    assert "Traceback" not in await client.finish()
