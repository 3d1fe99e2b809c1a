"""The registry's notifications cost what a change touches, not the size of the graph."""

from __future__ import annotations

from collections import Counter

from services.core.registry import Registry
from services.runtime.protocol import Entity, ForeignNode, NodeDescription, PublishersFrame

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


def test_a_bridge_lists_the_ros2_nodes_it_sees_and_they_leave_with_it() -> None:
    registry = Registry()
    talker = ForeignNode(
        name="/talker",
        system="ros2",
        publications=[Entity(name="/chatter", type="std_msgs/msg/String")],
        services=[Entity(name="/add", type="std_srvs/srv/Trigger")],
    )
    shadow = ForeignNode(name="/sim", system="ros2")  # a Skydeck node's name: listed once, as Skydeck's
    bridge = NodeDescription(
        name="/ros2_bridge", url="http://b", pid=2,
        publications=[Entity(name="/chatter", type="std_msgs/msg/String")], foreign=[talker, shadow],
    )
    registry.register(NodeDescription(name="/sim", url="http://s", pid=1), lambda frame: None)
    registry.register(bridge, lambda frame: None)
    graph = registry.graph()
    nodes = {node["name"]: node for node in graph["nodes"]}
    assert nodes["/talker"] == {
        "name": "/talker", "url": "", "pid": None, "publications": ["/chatter"], "subscriptions": [],
        "services": ["/add"], "system": "ros2", "via": "/ros2_bridge",
    }
    assert "system" not in nodes["/sim"]
    (chatter,) = graph["topics"]
    assert chatter["publishers"] == ["/ros2_bridge", "/talker"]
    assert graph["services"] == []  # the bridge hosts a bridged service in Skydeck, not the ROS 2 node
    assert registry.publishers("/chatter")[0].node == "/ros2_bridge"  # nobody links to a foreign node
    assert len(registry.publishers("/chatter")) == 1
    registry.unregister("/ros2_bridge", registry.nodes["/ros2_bridge"].inbox)
    assert [node["name"] for node in registry.graph()["nodes"]] == ["/sim"]
