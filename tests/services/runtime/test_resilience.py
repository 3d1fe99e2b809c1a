"""Trouble: a node before the core, a core restart, a publisher that dies and returns."""

from __future__ import annotations

import asyncio
import logging

from services.runtime import Node, NodeSettings
from shared_models.std_msgs import Int32
from tests.conftest import CoreProcess, free_port, wait_until


class Counter(Node):
    def __init__(self, settings, port: int = 0) -> None:
        super().__init__("counter", settings=settings.model_copy(update={"port": port}))
        self.publisher = self.create_publisher(Int32, "/count", 10)


class Collector(Node):
    def __init__(self, settings) -> None:
        super().__init__("collector", settings=settings)
        self.values: list[int] = []
        self.create_subscription(Int32, "/count", lambda m: self.values.append(m.data), 1000)


def _settings(core_url: str) -> NodeSettings:
    return NodeSettings(core_url=core_url, port=0, ping_interval_s=0.5, ping_timeout_s=1.0)


async def _linked(node: Node) -> None:
    await wait_until(lambda: node._participant.links, what="a link")
    for link, _ in list(node._participant.links.values()):
        await asyncio.wait_for(link.connected.wait(), 5)


async def test_node_started_before_core_waits_once_then_registers(caplog) -> None:
    caplog.set_level(logging.INFO, logger="skydeck.runtime")
    core = CoreProcess()
    node = Collector(_settings(core.url))
    await node.start()
    try:
        await wait_until(lambda: "waiting for core at" in caplog.text, what="the waiting line")
        await asyncio.sleep(0.6)  # several retry periods pass: the line must not repeat
        assert caplog.text.count("waiting for core at") == 1
        await core.start()
        await wait_until(lambda: "/collector" in core.registry.nodes, what="registration")
    finally:
        await node.stop()
        await core.stop()


async def test_a_node_started_beside_its_core_waits_quietly_while_it_starts(caplog) -> None:
    # `skydeck launch` starts its nodes with the core: they wait its grace without a warning,
    # ask often, and say it only if the core is still not there after it
    caplog.set_level(logging.INFO, logger="skydeck.runtime")
    core = CoreProcess()
    node = Collector(_settings(core.url).model_copy(update={"core_start_grace_s": 0.8}))
    await node.start()
    try:
        await asyncio.sleep(0.4)  # retries inside the grace: nothing said
        assert "waiting for core at" not in caplog.text
        await wait_until(lambda: "waiting for core at" in caplog.text, what="the line once the grace is over")
        await core.start()
        await wait_until(lambda: "/collector" in core.registry.nodes, what="registration")
    finally:
        await node.stop()
        await core.stop()
    assert caplog.text.count("waiting for core at") == 1


async def test_core_restart_streams_keep_flowing_and_nodes_register_again() -> None:
    core = CoreProcess()
    await core.start()
    counter = Counter(_settings(core.url))
    collector = Collector(_settings(core.url))
    await counter.start()
    await collector.start()
    try:
        await _linked(collector)
        await core.stop()
        # With the core gone, the direct node-to-node stream still delivers.
        for i in range(5):
            counter.publisher.publish(Int32(data=i))
        await wait_until(lambda: collector.values[-1:] == [4], what="messages while the core is down")
        restarted = CoreProcess(port=core.port)
        await restarted.start()
        await wait_until(
            lambda: {"/counter", "/collector"} <= restarted.registry.nodes.keys(),
            timeout_s=3.0,
            what="both nodes to register again",
        )
        await restarted.stop()
    finally:
        await collector.stop()
        await counter.stop()


async def test_subscriber_reconnects_when_publisher_returns(core) -> None:
    port = free_port()
    collector = Collector(_settings(core.url))
    await collector.start()
    first = Counter(_settings(core.url), port=port)
    await first.start()
    try:
        await _linked(collector)
        first.publisher.publish(Int32(data=1))
        await wait_until(lambda: collector.values == [1], what="the first message")
        await first.stop()
        await wait_until(lambda: "/counter" not in core.registry.nodes, what="the publisher to leave")
        second = Counter(_settings(core.url), port=port)
        await second.start()
        await _linked(collector)
        second.publisher.publish(Int32(data=2))
        await wait_until(lambda: collector.values == [1, 2], what="a message from the new publisher")
        await second.stop()
    finally:
        await collector.stop()
