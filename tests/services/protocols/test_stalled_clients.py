"""A protocol client that stops reading is treated like a stalled native reader: its frames wait
in its own bounded queue, it is detached and closed with 4001 (docs/streams.md), and the
publisher and every other client go on at their own pace."""

from __future__ import annotations

import asyncio
import json
import struct
from collections.abc import AsyncIterator, Awaitable, Callable
from typing import Any

import pytest
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosed
from websockets.typing import Subprotocol

from services.runtime import Node, NodeSettings
from shared_models.std_msgs import String
from tests.conftest import wait_until
from tests.services.protocols.conftest import Bridge

pytestmark = pytest.mark.timeout(120)

TOPIC = "/flood/data"
V1 = [Subprotocol("foxglove.websocket.v1")]


class Flood(Node):
    """Publishes numbered 4 KiB strings on /flood/data when told to."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("flood", settings=settings)
        self.publisher = self.create_publisher(String, TOPIC, 10)
        self.sent = 0

    def burst(self, count: int) -> None:
        for _ in range(count):
            self.publisher.publish(String(data=f"{self.sent:08d}" + "x" * 4096))
            self.sent += 1


@pytest.fixture
async def flood(impatient_bridge: Bridge) -> AsyncIterator[Flood]:
    node = Flood(NodeSettings(core_url=impatient_bridge.core_url, port=0))
    await node.start()
    await wait_until(lambda: impatient_bridge.core.registry.topic_type(TOPIC) is not None, what="the flood topic")
    yield node
    await node.stop()


# Each protocol's way to open a subscription to TOPIC, and to read the number of a message.
Subscribe = Callable[[Bridge, int], Awaitable[ClientConnection]]


async def _rosbridge(bridge: Bridge, max_queue: int) -> ClientConnection:
    ws = await connect(bridge.rosbridge_url, max_queue=max_queue)
    await ws.send(json.dumps({"op": "subscribe", "topic": TOPIC, "queue_length": 10_000}))
    return ws


async def _foxglove(bridge: Bridge, max_queue: int) -> ClientConnection:
    ws = await connect(bridge.foxglove_url, subprotocols=V1, max_queue=max_queue)
    async with asyncio.timeout(10):
        while True:
            message = await ws.recv()
            if isinstance(message, str) and (parsed := json.loads(message))["op"] == "advertise":
                channel = next((c["id"] for c in parsed["channels"] if c["topic"] == TOPIC), None)
                if channel is not None:
                    break
    await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": channel}]}))
    return ws


def _clients(bridge: Bridge) -> list[str]:
    """The protocol clients subscribed to TOPIC, by their names in the graph."""
    return [n for n in bridge.core.registry.subscribers(TOPIC) if n.startswith(("/rosbridge_client_", "/foxglove_client_"))]


def _number(frame: str | bytes) -> int | None:
    """The flood message's number, or None for a frame of something else."""
    if isinstance(frame, bytes):
        if frame[0] != 0x01 or struct.unpack_from("<I", frame, 1)[0] != 1:
            return None
        data: str = json.loads(frame[13:])["data"]
    else:
        message: dict[str, Any] = json.loads(frame)
        if message.get("op") != "publish":
            return None
        data = message["msg"]["data"]
    return int(data[:8])


@pytest.mark.parametrize("subscribe", [_rosbridge, _foxglove], ids=["rosbridge", "foxglove"])
async def test_a_client_that_stops_reading_is_closed_with_4001_and_others_go_on(
    impatient_bridge: Bridge, flood: Flood, subscribe: Subscribe
) -> None:
    bridge = impatient_bridge
    registry = bridge.core.registry
    # This client takes one frame into its buffer and then stops reading: TCP fills up behind it.
    stalled = await subscribe(bridge, 1)
    await wait_until(lambda: len(_clients(bridge)) == 1, what="the stalled client to subscribe")
    (stalled_name,) = _clients(bridge)
    bystander = await subscribe(bridge, 16)
    await wait_until(lambda: len(_clients(bridge)) == 2, what="the bystander to subscribe")
    last_seen = -1

    async def read_bystander() -> None:
        nonlocal last_seen
        async for frame in bystander:
            number = _number(frame)
            if number is not None:
                last_seen = number

    reading = asyncio.create_task(read_bystander())
    try:
        # Publish, never waiting for any reader, until the core gives up on the stalled client.
        deadline = asyncio.get_running_loop().time() + 60
        while stalled_name in registry.nodes:
            assert asyncio.get_running_loop().time() < deadline, "the stalled client was never closed"
            flood.burst(50)
            await asyncio.sleep(0.005)
        # The bystander still gets what is published, up to the last message, and after.
        final = flood.sent - 1
        await wait_until(lambda: last_seen == final, timeout_s=20, what="the bystander to get the last message")
        flood.burst(1)
        await wait_until(lambda: last_seen == final + 1, timeout_s=10, what="the bystander to go on")
        assert not reading.done()
    finally:
        reading.cancel()
        await bystander.close()
    # The stalled client, reading at last, gets the frames it had, then a clean close with 4001.
    with pytest.raises(ConnectionClosed) as closed:
        while True:
            await asyncio.wait_for(stalled.recv(), 10)
    assert closed.value.rcvd is not None, "a reset, not a close frame"
    assert closed.value.rcvd.code == 4001 and "stalled" in closed.value.rcvd.reason
