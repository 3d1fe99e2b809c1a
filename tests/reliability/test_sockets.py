"""Sockets that misbehave: clients that vanish without closing (reaped by pings, on nodes and on
the core), a flood of publishers with readers that never read (memory stays bounded, a normal
reader still gets its messages), and service handlers that hang (callers get 504, others go on).
"""

from __future__ import annotations

import asyncio
import base64
import json
import os
import signal
import sys
from collections.abc import AsyncIterator
from pathlib import Path

import httpx
import pytest
from websockets.asyncio.client import connect

from services.launch.background import BackgroundProcess
from services.runtime import Node, NodeSettings
from services.runtime.edge.links import stream_url
from shared_models.std_msgs import Int32
from shared_models.std_srvs import Trigger, TriggerResponse
from tests.conftest import CoreProcess, await_registered, free_port, wait_until

FLOOD_NODE = Path(__file__).with_name("flood_node.py")


class Talker(Node):
    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("talker", settings=settings)
        self.publisher = self.create_publisher(Int32, "/count", 10)
        self.create_service(Trigger, "/talker/hang", self.hang)
        self.create_service(Trigger, "/talker/ok", lambda request: TriggerResponse(success=True, message="ok"))
        self.hanging = 0  # handlers entered and still waiting

    async def hang(self, request: object) -> TriggerResponse:
        self.hanging += 1
        await asyncio.Event().wait()  # never answers
        return TriggerResponse()


async def _vanishing_client(port: int, path: str) -> asyncio.StreamWriter:
    """A WebSocket client that completes the handshake, then never reads a frame or answers a
    ping, and never closes (a laptop whose lid was shut): the server must find out by itself."""
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    key = base64.b64encode(os.urandom(16)).decode()
    writer.write(
        f"GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
        f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n".encode()
    )
    status = await asyncio.wait_for(reader.readline(), 5)
    assert b" 101 " in status, status
    return writer


def _port(url: str) -> int:
    return int(url.rsplit(":", 1)[1])


@pytest.fixture
async def talker_factory() -> AsyncIterator:
    started: list[Node] = []

    async def start(**settings: object) -> Talker:
        node = Talker(NodeSettings(core_url=f"http://127.0.0.1:{free_port()}", port=0, **settings))  # type: ignore[arg-type]
        await node.start()
        started.append(node)
        return node

    yield start
    for node in started:
        await node.stop()


@pytest.mark.parametrize("pings", [True, False], ids=["pings", "no-pings-control"])
async def test_vanished_clients_are_reaped_by_pings_and_others_go_on(talker_factory, pings: bool) -> None:
    # With pings every 0.2 s and 0.3 s to answer, a silent socket is dropped within ~0.5 s. The
    # control case (pings an hour apart) shows that it is the pings that drop it.
    node = await talker_factory(ping_interval_s=0.2 if pings else 3600, ping_timeout_s=0.3 if pings else 3600)
    outboxes = node._participant.endpoints["/count"].outboxes
    vanished = [await _vanishing_client(_port(node.url), "/count") for _ in range(5)]
    try:
        async with connect(stream_url(node.url, "/count")) as healthy:
            await wait_until(lambda: len(outboxes) == 6, what="six readers")
            if pings:
                await wait_until(lambda: len(outboxes) == 1, timeout_s=5, what="the vanished readers to be reaped")
            else:
                await asyncio.sleep(1.5)  # three times the reaping time above
                assert len(outboxes) == 6
            node.publisher.publish(Int32(data=42))
            assert json.loads(await asyncio.wait_for(healthy.recv(), 5)) == {"data": 42}
    finally:
        for writer in vanished:
            writer.close()


@pytest.mark.timeout(60)
async def test_core_reaps_vanished_gateway_readers() -> None:
    """The real `skydeck core` with short pings: a vanished reader of ws://core/count is dropped,
    and with the last reader gone the core closes its link to the publisher."""
    port = free_port()
    env = {**os.environ, "SKYDECK_PING_INTERVAL_S": "0.2", "SKYDECK_PING_TIMEOUT_S": "0.3"}
    core = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "core", "--port", str(port), "--rosbridge-port", "0", "--foxglove-port", "0"],
        name="core", env=env,
    )
    core_url = f"http://127.0.0.1:{port}"
    node = Talker(NodeSettings(core_url=core_url, port=0, ping_interval_s=3600, ping_timeout_s=3600))
    try:
        await asyncio.to_thread(core.wait_healthy, core_url + "/health", 20)
        await node.start()
        await await_registered(core_url, {"/talker"}, timeout_s=20)
        outboxes = node._participant.endpoints["/count"].outboxes
        writer = await _vanishing_client(port, "/count")
        try:
            await wait_until(lambda: len(outboxes) == 1, what="the core's link to the publisher")
            await wait_until(lambda: len(outboxes) == 0, timeout_s=5, what="the core to reap the reader and unlink")
        finally:
            writer.close()
    finally:
        await node.stop()
        core.stop(signal.SIGTERM)


def _rss_bytes(pid: int) -> int:
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise AssertionError("no VmRSS")


@pytest.mark.timeout(90)
@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="reads the process's RSS from /proc")
async def test_flood_of_publishers_and_stalled_readers_keeps_memory_bounded() -> None:
    """20 clients publish 1 KiB frames as fast as they can to a node that echoes each one to 20
    readers that never read and to one that does. Unbounded buffering would hold
    40,000 frames x 20 readers (~800 MB); the outboxes hold at most 100 each."""
    port = free_port()
    env = {**os.environ, "SKYDECK_CORE_URL": f"http://127.0.0.1:{free_port()}"}
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "run", str(FLOOD_NODE), "--port", str(port)], name="flood node", env=env
    )
    url = f"http://127.0.0.1:{port}"
    stalled: list[asyncio.StreamWriter] = []
    try:
        await asyncio.to_thread(process.wait_healthy, url + "/health", 20)
        stalled = [await _vanishing_client(port, "/flood/out") for _ in range(20)]
        payload = "x" * 1024
        publishers, frames_each = 20, 2000

        async def flood(index: int) -> None:
            async with connect(stream_url(url, "/flood/in")) as websocket:
                for i in range(frames_each):
                    await websocket.send(json.dumps({"data": f"{index}:{i}:{payload}"}))

        received: list[str] = []
        async with connect(stream_url(url, "/flood/out", queue=10_000), max_size=None) as reader:

            async def read() -> None:
                async for frame in reader:
                    received.append(json.loads(frame)["data"])

            reading = asyncio.create_task(read())
            await asyncio.sleep(0.2)
            before = _rss_bytes(process.pid)
            for _ in range(2):  # two rounds: a leak would grow with each
                await asyncio.gather(*(flood(i) for i in range(publishers)))
            after = _rss_bytes(process.pid)
            # The node still serves: a last message reaches the reading client.
            async with connect(stream_url(url, "/flood/in")) as websocket:
                await websocket.send(json.dumps({"data": "the end"}))
            await wait_until(lambda: "the end" in received, timeout_s=20, what="the reader to get the last message")
            reading.cancel()
        assert len(received) > 1000  # it got messages all along, not only the last
        assert after - before < 100 * 2**20, f"RSS grew by {(after - before) / 2**20:.0f} MiB"
        print(f"flood: {2 * publishers * frames_each} frames in, RSS {before / 2**20:.0f} -> {after / 2**20:.0f} MiB, "
              f"reader got {len(received)}")
    finally:
        for writer in stalled:
            writer.close()
        process.stop(signal.SIGTERM)


async def test_hung_handlers_time_out_at_the_gateway_and_do_not_block_others() -> None:
    # The gateway's timeout is long enough that the other calls below are answered well within it
    # even on a loaded machine; the twenty hung calls are awaited inside the node before they start.
    core = CoreProcess(gateway_timeout_s=5.0)
    await core.start()
    node = Talker(NodeSettings(core_url=core.url, port=0))
    await node.start()
    try:
        await wait_until(lambda: "/talker" in core.registry.nodes, what="registration")
        async with httpx.AsyncClient(timeout=30) as http:
            hung = [asyncio.create_task(http.post(core.url + "/talker/hang")) for _ in range(20)]
            await wait_until(lambda: node.hanging == 20, what="the twenty calls to reach the node")
            ok = await http.post(core.url + "/talker/ok")
            graph = await http.get(core.url + "/api/graph")
            # The other calls were answered while all twenty hung calls were still waiting.
            assert not any(task.done() for task in hung)
            assert ok.status_code == 200 and ok.json()["message"] == "ok"
            assert graph.status_code == 200
            replies = await asyncio.gather(*hung)
        assert {reply.status_code for reply in replies} == {504}
        assert all("did not answer within 5 s" in reply.json()["detail"] for reply in replies)
    finally:
        await node.stop()
        await core.stop()
