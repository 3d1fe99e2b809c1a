"""The registry's notifications cost what a change touches, not the size of the graph."""

from __future__ import annotations

from collections import Counter

from services.core.registry import Registry
from services.runtime.protocol import Entity, NodeDescription, PublishersFrame

TWIST = "geometry_msgs/msg/Twist"


def _node(name: str, *, publishes: tuple[str, ...] = (), subscribes: tuple[str, ...] = ()) -> NodeDescription:
    return NodeDescription(
        name=name,
        url=f"http://127.0.0.1/{name.strip('/')}",
        pid=1,
        publications=[Entity(name=t, type=TWIST) for t in publishes],
        subscriptions=[Entity(name=t, type=TWIST) for t in subscribes],
    )


def _graph_of(count: int) -> tuple[Registry, Counter[str]]:
    """``count`` nodes, each subscribing to its own topic; the frames each is sent are counted."""
    registry = Registry()
    told: Counter[str] = Counter()
    for index in range(count):
        name = f"/n{index}"
        registry.register(_node(name, subscribes=(f"/t{index}",)), lambda frame, name=name: told.update([name]))
    return registry, told


def test_a_new_publisher_tells_only_the_subscribers_of_its_topic(monkeypatch) -> None:
    registry, told = _graph_of(200)
    told.clear()
    looked_up: list[str] = []
    publishers = registry.publishers
    monkeypatch.setattr(registry, "publishers", lambda topic: looked_up.append(topic) or publishers(topic))
    received: list[PublishersFrame] = []
    registry.register(_node("/talker", publishes=("/t7",)), received.append)
    assert told == Counter({"/n7": 1})
    assert received == []  # it subscribes to nothing
    # The work is the one topic that changed, not every subscription in the graph (O(n) per
    # change, not O(n^2)): the old registry looked up all 200 topics here.
    assert looked_up == ["/t7"]


def test_registering_tells_the_newcomer_only_about_its_own_topics() -> None:
    registry, told = _graph_of(200)
    registry.register(_node("/talker", publishes=("/t3",)), lambda frame: None)
    received: list[PublishersFrame] = []
    registry.register(_node("/listener", subscribes=("/t3", "/t4")), received.append)
    assert sorted((f.topic, [p.node for p in f.publishers]) for f in received) == [("/t3", ["/talker"]), ("/t4", [])]


def test_unsubscribing_and_subscribing_again_is_told_again() -> None:
    registry = Registry()
    registry.register(_node("/talker", publishes=("/x",)), lambda frame: None)
    received: list[PublishersFrame] = []
    inbox = received.append
    registry.register(_node("/listener", subscribes=("/x",)), inbox)
    registry.update(_node("/listener"), inbox)
    registry.update(_node("/listener", subscribes=("/x",)), inbox)
    assert [f.topic for f in received] == ["/x", "/x"]


def test_a_publisher_leaving_tells_its_subscribers() -> None:
    registry = Registry()
    talker_inbox = lambda frame: None  # noqa: E731
    registry.register(_node("/talker", publishes=("/x",)), talker_inbox)
    received: list[PublishersFrame] = []
    registry.register(_node("/listener", subscribes=("/x",)), received.append)
    registry.unregister("/talker", talker_inbox)
    assert [[p.node for p in f.publishers] for f in received] == [["/talker"], []]
    assert registry.publishers("/x") == [] and registry.topic_type("/x") == TWIST
