"""Publishing and subscribing between real nodes, on real sockets, through the core's registry."""

from __future__ import annotations

import asyncio

import httpx
import pytest

from services.runtime import Node, NodeError
from shared_models.geometry_msgs import Point, PointStamped, Twist
from shared_models.std_msgs import Header, String
from tests.conftest import wait_until


class Talker(Node):
    def __init__(self, settings, *, latched: bool = False) -> None:
        super().__init__("talker", settings=settings)
        self.publisher = self.create_publisher(PointStamped, "my_point", 10, latched=latched)

    def send(self, x: float) -> None:
        header = Header(stamp=self.get_clock().now().to_msg(), frame_id="odom")
        self.publisher.publish(PointStamped(header=header, point=Point(x=x, y=2.0, z=0.0)))


class Listener(Node):
    def __init__(self, settings, name: str = "listener") -> None:
        super().__init__(name, settings=settings)
        self.received: list[PointStamped] = []
        self.got = asyncio.Event()
        self.create_subscription(PointStamped, "/my_point", self.on_point, 100)

    def on_point(self, msg: PointStamped) -> None:
        self.received.append(msg)
        self.got.set()


async def test_messages_flow_between_nodes_with_seq_filled(start_node) -> None:
    talker = await start_node(Talker)
    listener = await start_node(Listener)
    # The listener links to the talker as soon as the core pushes the publisher list.
    await wait_until(lambda: listener._participant.links, what="listener to link to the talker")
    for link, _ in listener._participant.links.values():
        await asyncio.wait_for(link.connected.wait(), 5)
    for x in (1.0, 2.0, 3.0):
        talker.send(x)
    await wait_until(lambda: len(listener.received) == 3, what="three messages")
    assert [m.point.x for m in listener.received] == [1.0, 2.0, 3.0]
    assert [m.header.seq for m in listener.received] == [1, 2, 3]
    assert listener.received[0].header.frame_id == "odom"


async def test_publisher_refuses_wrong_type(start_node) -> None:
    talker = await start_node(Talker)
    with pytest.raises(TypeError, match="takes geometry_msgs/msg/PointStamped"):
        talker.publisher.publish(Twist())


async def test_topic_cannot_take_two_types(start_node) -> None:
    talker = await start_node(Talker)
    with pytest.raises(NodeError, match="already used with type"):
        talker.create_publisher(String, "/my_point", 1)


async def test_subscription_in_the_same_node_gets_messages_without_a_socket(start_node) -> None:
    talker = await start_node(Talker)
    got: list[PointStamped] = []
    event = asyncio.Event()
    talker.create_subscription(PointStamped, "/my_point", lambda m: (got.append(m), event.set()), 10)
    talker.send(7.0)
    await asyncio.wait_for(event.wait(), 5)
    assert got[0].point.x == 7.0
    assert not talker._participant.links


async def test_get_latest_message_on_node_and_gateway(core, start_node) -> None:
    talker = await start_node(Talker)
    async with httpx.AsyncClient() as http:
        missing = await http.get(talker.url + "/my_point")
        assert missing.status_code == 404
        assert "no message on /my_point yet" in missing.json()["detail"]
        talker.send(4.0)
        direct = await http.get(talker.url + "/my_point")
        through_core = await http.get(core.url + "/my_point")
    assert direct.json()["point"]["x"] == 4.0
    assert through_core.json() == direct.json()


async def test_latched_topic_reaches_late_subscriber(start_node) -> None:
    talker = await start_node(lambda s: Talker(s, latched=True))
    talker.send(9.0)
    listener = await start_node(Listener)
    await asyncio.wait_for(listener.got.wait(), 5)
    assert listener.received[0].point.x == 9.0


async def test_async_callbacks_and_timers_run(start_node) -> None:
    ticks = asyncio.Event()

    class Ticker(Node):
        def __init__(self, settings) -> None:
            super().__init__("ticker", settings=settings)
            self.count = 0
            self.create_timer(0.01, self.tick)

        async def tick(self) -> None:
            self.count += 1
            if self.count == 3:
                ticks.set()

    await start_node(Ticker)
    await asyncio.wait_for(ticks.wait(), 5)


async def test_failing_callback_is_logged_and_the_node_goes_on(start_node, caplog) -> None:
    talker = await start_node(Talker)
    calls: list[float] = []
    done = asyncio.Event()

    def flaky(msg: PointStamped) -> None:
        calls.append(msg.point.x)
        if len(calls) == 1:
            raise RuntimeError("boom")
        done.set()

    talker.create_subscription(PointStamped, "/my_point", flaky, 10)
    talker.send(1.0)
    talker.send(2.0)
    await asyncio.wait_for(done.wait(), 5)
    assert calls == [1.0, 2.0]
    assert "raised; the node keeps running" in caplog.text


async def test_destroyed_node_refuses_new_entities(start_node) -> None:
    talker = await start_node(Talker)
    talker.destroy_node()
    with pytest.raises(NodeError, match="destroyed"):
        talker.create_publisher(String, "/chatter", 1)


async def test_rosout_carries_log_lines(core, start_node) -> None:
    from shared_models.rcl_interfaces import Log

    logs: list[Log] = []
    got = asyncio.Event()

    class Watcher(Node):
        def __init__(self, settings) -> None:
            super().__init__("watcher", settings=settings)
            self.create_subscription(Log, "/rosout", lambda m: (logs.append(m), got.set()), 10)

    talker = await start_node(Talker)
    watcher = await start_node(Watcher)
    await wait_until(lambda: any(k[1] == talker.url for k in watcher._participant.links), what="watcher to link")
    for link, _ in watcher._participant.links.values():
        await asyncio.wait_for(link.connected.wait(), 5)
    talker.get_logger().info("taking off from %s", "pad 1")
    await wait_until(lambda: any(m.msg == "taking off from pad 1" for m in logs), what="the log line")
    line = next(m for m in logs if m.msg == "taking off from pad 1")
    assert line.name == "/talker" and line.level == Log.INFO
