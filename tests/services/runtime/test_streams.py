"""The WebSocket edge: client publishing, bad frames, options, slow readers."""

from __future__ import annotations

import asyncio
import json

import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from services.runtime import Node
from services.runtime.edge.links import stream_url
from shared_models.geometry_msgs import Twist
from tests.bad_frames import oversized_header
from tests.conftest import wait_until


class Teleop(Node):
    """Subscribes /drone/cmd_vel and publishes /echo of what it receives."""

    def __init__(self, settings) -> None:
        super().__init__("teleop_sink", settings=settings)
        self.received: list[Twist] = []
        self.create_subscription(Twist, "/drone/cmd_vel", self.received.append, 100)
        self.publisher = self.create_publisher(Twist, "/echo", 10)


async def _closed(websocket) -> tuple[int, str]:
    with pytest.raises(ConnectionClosed):
        await asyncio.wait_for(websocket.recv(), 5)
    return websocket.close_code, websocket.close_reason


@pytest.mark.parametrize("via_core", [False, True])
async def test_client_frames_are_published_to_subscribers(core, start_node, via_core) -> None:
    sink = await start_node(Teleop)
    base = core.url if via_core else sink.url
    async with connect(stream_url(base, "/drone/cmd_vel")) as websocket:
        await websocket.send(json.dumps({"linear": {"x": 1.5, "y": 0.0, "z": 0.0}}))
        await wait_until(lambda: len(sink.received) == 1, what="the frame to reach the subscriber")
    assert sink.received[0].linear.x == 1.5


@pytest.mark.parametrize("via_core", [False, True])
async def test_invalid_frame_closes_only_that_socket_with_1007(core, start_node, via_core) -> None:
    sink = await start_node(Teleop)
    base = core.url if via_core else sink.url
    async with connect(stream_url(base, "/drone/cmd_vel")) as good, connect(stream_url(base, "/drone/cmd_vel")) as bad:
        await bad.send(json.dumps({"linear": {"x": "fast"}}))
        code, reason = await _closed(bad)
        assert code == 1007
        assert "linear.x" in reason
        await good.send(json.dumps({"linear": {"x": 2.0}}))
        await wait_until(lambda: any(t.linear.x == 2.0 for t in sink.received), what="the good socket to keep working")


async def test_not_json_and_unknown_field_close_with_1007(start_node) -> None:
    sink = await start_node(Teleop)
    for frame, expected in (("{not json", "invalid"), (json.dumps({"linear": {"w": 1}}), "linear.w")):
        async with connect(stream_url(sink.url, "/drone/cmd_vel")) as websocket:
            await websocket.send(frame)
            code, reason = await _closed(websocket)
            assert code == 1007 and expected in reason


async def test_non_finite_values_are_refused(start_node) -> None:
    sink = await start_node(Teleop)
    async with connect(stream_url(sink.url, "/drone/cmd_vel")) as websocket:
        await websocket.send('{"linear": {"x": NaN}}')
        code, _ = await _closed(websocket)
    assert code == 1007 and sink.received == []


async def test_binary_frame_closes_with_1003(start_node) -> None:
    sink = await start_node(Teleop)
    async with connect(stream_url(sink.url, "/drone/cmd_vel")) as websocket:
        await websocket.send(b"\x00\x01")
        code, reason = await _closed(websocket)
    assert code == 1003 and "binary" in reason


async def test_oversized_frame_closes_with_1009(core, start_node) -> None:
    sink = await start_node(Teleop)
    async with connect(stream_url(sink.url, "/drone/cmd_vel"), max_size=None) as websocket:
        websocket.transport.write(oversized_header(sink.settings.max_message_bytes + 10))
        code, _ = await _closed(websocket)
    assert code == 1009
    async with connect(stream_url(sink.url, "/drone/cmd_vel")) as websocket:
        await websocket.send(json.dumps({"linear": {"x": 3.0}}))
        await wait_until(lambda: any(t.linear.x == 3.0 for t in sink.received), what="the node to keep serving")


@pytest.mark.parametrize("query", ["queue=0", "queue=abc", "rate=-1", "rate=nan", "batch=2"])
async def test_bad_options_close_with_1008(start_node, query) -> None:
    sink = await start_node(Teleop)
    async with connect(stream_url(sink.url, "/echo") + "?" + query) as websocket:
        code, reason = await _closed(websocket)
    assert code == 1008 and query.split("=")[0] in reason


def _patient(settings):  # type: ignore[no-untyped-def]
    """Settings under which a reader that reads late is slow, not stalled, and keepalive waits."""
    return settings.model_copy(update={"ping_interval_s": 5.0, "ping_timeout_s": 60.0, "stall_timeout_s": 50.0})


async def test_slow_reader_loses_oldest_and_does_not_slow_others(start_node) -> None:
    sink = await start_node(lambda settings: Teleop(_patient(settings)))
    outboxes = sink._participant.endpoints["/echo"].outboxes
    # No keepalive from this client: it stops reading on purpose, so the server's pong would
    # wait behind megabytes of unread frames, and on a loaded machine the client's own ping
    # timeout (20 s) would end the connection mid-test without a close frame.
    async with connect(stream_url(sink.url, "/echo", queue=5), max_queue=1, ping_interval=None) as slow:
        await wait_until(lambda: len(outboxes) == 1, what="the slow reader")
        (slow_outbox,) = outboxes
        async with connect(stream_url(sink.url, "/echo")) as fast:
            await wait_until(lambda: len(outboxes) == 2, what="both readers")
            # Publish until the slow reader's socket has backed up (kernel buffers hold
            # megabytes) and its outbox drops; the publisher never waits for it.
            published = 0
            deadline = asyncio.get_running_loop().time() + 30
            while slow_outbox.dropped == 0:
                assert asyncio.get_running_loop().time() < deadline, "the slow reader's outbox never dropped"
                for _ in range(500):
                    sink.publisher.publish(Twist(linear={"x": float(published)}))
                    published += 1
                await asyncio.sleep(0)
            final = float(published - 1)
            # The fast reader gets the last message; the slow one still ends on it, having lost
            # the middle.
            last = None
            while last != final:
                last = json.loads(await asyncio.wait_for(fast.recv(), 5))["linear"]["x"]
            received = []
            while not received or received[-1] != final:
                received.append(json.loads(await asyncio.wait_for(slow.recv(), 5))["linear"]["x"])
            assert len(received) < published


async def test_a_stalled_reader_is_closed_with_4001_and_the_others_keep_their_rate(start_node) -> None:
    sink = await start_node(
        lambda settings: Teleop(settings.model_copy(update={"ping_interval_s": 5.0, "ping_timeout_s": 60.0, "stall_timeout_s": 1.0}))
    )
    outboxes = sink._participant.endpoints["/echo"].outboxes
    async with connect(stream_url(sink.url, "/echo", queue=5), max_queue=1, ping_interval=None) as stalled:  # no keepalive: see the test above
        await wait_until(lambda: len(outboxes) == 1, what="the stalled reader")
        (stalled_outbox,) = outboxes
        async with connect(stream_url(sink.url, "/echo", queue=10_000), max_size=None) as fast:
            await wait_until(lambda: len(outboxes) == 2, what="both readers")
            sent = 0
            fast_count = 0

            async def read_fast() -> None:
                nonlocal fast_count
                async for _ in fast:
                    fast_count += 1

            reading = asyncio.create_task(read_fast())
            try:
                # Publish (never reading the stalled socket) until the edge gives up on it.
                deadline = asyncio.get_running_loop().time() + 30
                while stalled_outbox in outboxes:
                    assert asyncio.get_running_loop().time() < deadline, "the stalled reader was never closed"
                    for _ in range(200):
                        sink.publisher.publish(Twist(linear={"x": float(sent)}))
                        sent += 1
                    await asyncio.sleep(0.001)
                # The fast reader kept up with everything published, during the stall and after.
                await wait_until(lambda: fast_count == sent, timeout_s=20, what="the fast reader to catch up")
            finally:
                reading.cancel()
        # The stalled reader, reading at last, gets what it had, then a clean close with 4001.
        with pytest.raises(ConnectionClosed) as closed:
            while True:
                await asyncio.wait_for(stalled.recv(), 10)
    assert closed.value.rcvd is not None, "a reset, not a close frame"
    assert closed.value.rcvd.code == 4001 and "stalled" in closed.value.rcvd.reason


async def test_rate_option_throttles_to_newest(start_node) -> None:
    sink = await start_node(Teleop)
    async with connect(stream_url(sink.url, "/echo", rate=5)) as websocket:
        await wait_until(lambda: sink._participant.endpoints["/echo"].outboxes, what="the reader")
        for i in range(100):
            sink.publisher.publish(Twist(linear={"x": float(i)}))
        first = json.loads(await asyncio.wait_for(websocket.recv(), 5))
    assert first["linear"]["x"] == 99.0
