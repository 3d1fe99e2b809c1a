"""The one topic edge: socket modes, no echo, frames forwarded as sent, on a node and on the core."""

from __future__ import annotations

import asyncio
import json

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from services.runtime.edge.frames import is_complete
from services.runtime.edge.links import stream_url
from services.runtime.wire import Close, wire_description
from shared_models.geometry_msgs import Point, PointStamped, Twist
from tests.conftest import wait_until
from tests.services.runtime.test_streams import (
    Teleop as Echo,  # publishes /echo, subscribes /drone/cmd_vel
)

pytestmark = pytest.mark.timeout(60)


async def _next(websocket, timeout_s: float = 5.0) -> dict:
    return json.loads(await asyncio.wait_for(websocket.recv(), timeout_s))


async def _nothing_within(websocket, seconds: float) -> bool:
    try:
        await asyncio.wait_for(websocket.recv(), seconds)
    except TimeoutError:
        return True
    return False


@pytest.mark.parametrize("via_core", [False, True])
async def test_a_publisher_is_never_sent_its_own_frames(core, start_node, via_core) -> None:
    node = await start_node(Echo)
    base = core.url if via_core else node.url
    async with connect(stream_url(base, "/echo")) as reader, connect(stream_url(base, "/echo")) as writer:
        await wait_until(lambda: len(node._participant.endpoints["/echo"].outboxes) >= 1, what="readers")
        await writer.send(json.dumps({"linear": {"x": 4.0}}))
        assert (await _next(reader))["linear"]["x"] == 4.0
        assert await _nothing_within(writer, 0.5)  # no echo of its own frame


async def test_publish_mode_reads_nothing_and_subscribe_mode_may_not_publish(core, start_node) -> None:
    node = await start_node(Echo)
    async with connect(stream_url(core.url, "/drone/cmd_vel", mode="publish")) as publisher:
        await publisher.send(json.dumps({"linear": {"x": 2.0}}))
        await wait_until(lambda: any(t.linear.x == 2.0 for t in node.received), what="the frame to arrive")
    # a publish-only socket makes the core publish the topic, but not subscribe to it
    graph = core.registry.graph()
    (core_node,) = [n for n in graph["nodes"] if n["name"] == "/skydeck_core"]
    assert "/drone/cmd_vel" in core_node["publications"] and "/drone/cmd_vel" not in core_node["subscriptions"]
    async with connect(stream_url(node.url, "/echo", mode="subscribe")) as reader:
        await reader.send(json.dumps({"linear": {"x": 1.0}}))
        with pytest.raises(ConnectionClosed):
            await asyncio.wait_for(reader.recv(), 5)
        assert reader.close_code == Close.UNSUPPORTED


async def test_an_unknown_mode_closes_with_1008(start_node) -> None:
    node = await start_node(Echo)
    async with connect(stream_url(node.url, "/echo", mode="both_ways")) as websocket:
        with pytest.raises(ConnectionClosed):
            await asyncio.wait_for(websocket.recv(), 5)
    assert websocket.close_code == Close.POLICY and "mode" in websocket.close_reason


async def test_complete_frames_go_on_as_sent_and_partial_ones_are_completed(core, start_node) -> None:
    await start_node(Echo)
    complete = '{"linear": {"x": 1.5, "y": 0, "z": 0},   "angular": {"x": 0, "y": 0, "z": 0.25}}'
    async with connect(stream_url(core.url, "/drone/cmd_vel", mode="subscribe")) as reader:
        await wait_until(lambda: core.registry.subscribers("/drone/cmd_vel"), what="the core to read")
        async with connect(stream_url(core.url, "/drone/cmd_vel", mode="publish")) as writer:
            await writer.send(complete)
            assert await asyncio.wait_for(reader.recv(), 5) == complete  # byte for byte: not re-serialised
            await writer.send('{"linear": {"x": 2.5}}')
            assert json.loads(await asyncio.wait_for(reader.recv(), 5)) == Twist(linear={"x": 2.5}).model_dump()


def test_completeness_looks_at_every_depth() -> None:
    whole = PointStamped.model_validate_json(
        '{"header": {"seq": 0, "stamp": {"sec": 1, "nanosec": 2}, "frame_id": "map"}, "point": {"x": 1, "y": 2, "z": 3}}'
    )
    assert is_complete(whole)
    assert not is_complete(PointStamped.model_validate_json('{"header": {"frame_id": "map"}, "point": {"x": 1, "y": 2, "z": 3}}'))
    assert not is_complete(PointStamped(point=Point(x=1.0)))


async def test_the_core_serves_the_wire_constants_the_dashboard_uses(core) -> None:
    async with httpx.AsyncClient() as http:
        config = (await http.get(core.url + "/api/config")).json()
    assert config["close_codes"]["invalid_frame"] == 1007 == Close.INVALID_FRAME
    assert {key: config[key] for key in wire_description()} == wire_description()
    assert config["worlds"]["drone"]["fly_half_size_m"] > config["worlds"]["drone"]["arena_half_size_m"] > 0


async def test_the_core_node_stops_publishing_after_its_last_client_lingered(start_node) -> None:
    from tests.conftest import CoreProcess

    core = CoreProcess(gateway_linger_s=0.2)
    await core.start()
    try:
        async with connect(stream_url(core.url, "/ui_point", type="geometry_msgs/msg/PointStamped", mode="publish")) as w:
            await w.send(json.dumps({"point": {"x": 1.0}}))
            await wait_until(lambda: core.registry.publishers("/ui_point"), what="the core to publish")
        assert [p.node for p in core.registry.publishers("/ui_point")] == ["/skydeck_core"]
        await wait_until(lambda: not core.registry.publishers("/ui_point"), what="the linger to end")
        assert "/ui_point" not in core.app.state.core_node.participant.endpoints  # forgotten
    finally:
        await core.stop()
