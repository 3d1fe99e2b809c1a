"""``Publisher.publish_built``: a message made only when someone reads its topic (the
simulator's hot loop), numbered and counted like any other, and made on demand for ``GET``."""

from __future__ import annotations

import asyncio
import json

import httpx

from services.runtime import Node, NodeSettings
from shared_models.geometry_msgs import Point, PointStamped
from shared_models.std_msgs import Header, String
from tests.conftest import wait_until


class _Builds:
    """Builders of PointStamped messages that count what they made."""

    def __init__(self) -> None:
        self.made: list[float] = []

    def of(self, x: float):
        def build() -> PointStamped:
            self.made.append(x)
            return PointStamped(header=Header(frame_id="odom"), point=Point(x=x))

        return build


def test_an_unread_message_is_not_made_until_asked_for_and_keeps_its_number() -> None:
    node = Node("builder", settings=NodeSettings(port=0))
    publisher = node.create_publisher(PointStamped, "/p", 10)
    builds = _Builds()
    for x in (1.0, 2.0, 3.0):
        publisher.publish_built(builds.of(x))
    endpoint = publisher._endpoint
    assert builds.made == []
    assert endpoint.published_count == 3
    latest = json.loads(endpoint.latest_frame or "null")  # what GET /p answers
    assert builds.made == [3.0]  # only the latest, once
    assert latest["point"]["x"] == 3.0 and latest["header"]["seq"] == 3
    assert endpoint.latest_frame is not None and builds.made == [3.0]
    publisher.publish(PointStamped(point=Point(x=4.0)))  # the two ways share one count
    assert json.loads(endpoint.latest_frame or "null")["header"]["seq"] == 4


def test_a_headerless_message_is_deferred_the_same_way() -> None:
    node = Node("builder", settings=NodeSettings(port=0))
    publisher = node.create_publisher(String, "/s", 10)
    made: list[str] = []
    publisher.publish_built(lambda: (made.append("x"), String(data="hello"))[1])
    assert made == []
    assert json.loads(publisher._endpoint.latest_frame or "null") == {"data": "hello"}
    assert made == ["x"]


async def test_a_local_subscription_gets_each_message_made_at_once(start_node) -> None:
    node = await start_node(lambda settings: Node("builder", settings=settings))
    publisher = node.create_publisher(PointStamped, "/p", 10)
    got: list[PointStamped] = []
    node.create_subscription(PointStamped, "/p", got.append, 10)
    builds = _Builds()
    for x in (1.0, 2.0):
        publisher.publish_built(builds.of(x))
    assert builds.made == [1.0, 2.0]  # made in the publishing call, not later
    await wait_until(lambda: len(got) == 2, what="two messages to the local subscription")
    assert [(m.point.x, m.header.seq) for m in got] == [(1.0, 1), (2.0, 2)]


async def test_a_remote_subscriber_gets_them_and_get_answers_the_latest(start_node) -> None:
    node = await start_node(lambda settings: Node("builder", settings=settings))
    publisher = node.create_publisher(PointStamped, "/p", 10)
    builds = _Builds()
    publisher.publish_built(builds.of(0.5))
    assert builds.made == []
    listener = await start_node(lambda settings: Node("listener", settings=settings))
    got: list[PointStamped] = []
    arrived = asyncio.Event()
    listener.create_subscription(PointStamped, "/p", lambda m: (got.append(m), arrived.set()), 10)
    await wait_until(lambda: publisher.get_subscription_count() == 1, what="the listener's link")
    for x in (1.0, 2.0, 3.0):
        publisher.publish_built(builds.of(x))
    await wait_until(lambda: len(got) >= 3, what="three messages over the link")
    assert [m.point.x for m in got[-3:]] == [1.0, 2.0, 3.0]
    assert [m.header.seq for m in got[-3:]] == [2, 3, 4]
    async with httpx.AsyncClient(timeout=5.0) as http:
        latest = (await http.get(node.url + "/p")).json()
    assert latest["point"]["x"] == 3.0 and latest["header"]["seq"] == 4
