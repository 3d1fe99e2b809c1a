"""tf2 over real topics, in this process, against a real core: broadcasters and listeners on
rclpy nodes, static links latched and accumulated, waits that end when a broadcaster's data
arrives (the buffer fills on Skydeck's loop, so no spin is needed and a callback may wait), and
the one-line errors for a listener without a node."""

from __future__ import annotations

import math
import threading

import pytest

from services.ros.rospy.exceptions import ROSInitException
from services.ros.tf2_ros import (
    Buffer,
    StaticTransformBroadcaster,
    TransformBroadcaster,
    TransformListener,
)
from shared_models.builtin_interfaces import Time as TimeMsg
from shared_models.geometry_msgs import Quaternion, Transform, TransformStamped, Vector3
from shared_models.std_msgs import Header, Int32
from tests.ros.conftest import until

pytestmark = [pytest.mark.timeout(60)]


def _link(parent: str, child: str, nanoseconds: int, x: float, yaw: float = 0.0) -> TransformStamped:
    return TransformStamped(
        header=Header(stamp=TimeMsg.from_nsec(nanoseconds), frame_id=parent),
        child_frame_id=child,
        transform=Transform(translation=Vector3(x=x), rotation=Quaternion(z=math.sin(yaw / 2), w=math.cos(yaw / 2))),
    )


def test_static_links_accumulate_and_reach_a_listener_that_starts_later(rclpy) -> None:  # type: ignore[no-untyped-def]
    from services.ros.rclpy.time import Time

    broadcaster_node = rclpy.create_node("static_links")
    static = StaticTransformBroadcaster(broadcaster_node)
    static.sendTransform(_link("map", "odom", 0, x=1.0))
    static.sendTransform([_link("base_link", "laser", 0, x=0.1), _link("base_link", "camera", 0, x=0.2)])
    static.sendTransform(_link("map", "odom", 0, x=1.5))  # the same child again: replaced, not added
    listener_node = rclpy.create_node("late_listener")  # made after every send: the latch delivers
    buffer = Buffer()
    TransformListener(buffer, listener_node)
    until(lambda: buffer.can_transform("base_link", "camera", Time()) and buffer.can_transform("map", "odom", Time()), what="the static links")
    assert buffer.lookup_transform("base_link", "laser", Time()).transform.translation.x == pytest.approx(0.1)
    assert buffer.lookup_transform("map", "odom", Time()).transform.translation.x == pytest.approx(1.5)
    assert sorted(buffer.frame_names()) == ["base_link", "camera", "laser", "map", "odom"]


def test_a_lookup_waits_for_a_broadcasters_data_without_anyone_spinning(rclpy) -> None:  # type: ignore[no-untyped-def]
    from services.ros.rclpy.duration import Duration
    from services.ros.rclpy.time import Time

    talker = rclpy.create_node("tf_talker")
    listener_node = rclpy.create_node("tf_listener")
    buffer = Buffer()
    TransformListener(buffer, listener_node)  # nobody spins listener_node in this test
    broadcaster = TransformBroadcaster(talker)
    StaticTransformBroadcaster(talker).sendTransform(_link("map", "odom", 0, x=10.0))
    stop = threading.Event()

    def drive() -> None:
        step = 0
        while not stop.is_set():  # odom -> base_link at 20 Hz of stamps, x = t
            broadcaster.sendTransform([_link("odom", "base_link", step * 50_000_000, x=step * 0.05)])
            step += 1
            stop.wait(0.02)

    thread = threading.Thread(target=drive, daemon=True)
    thread.start()
    try:
        t = buffer.lookup_transform("map", "base_link", Time(seconds=1.0), timeout=Duration(seconds=20.0))
        assert t.transform.translation.x == pytest.approx(11.0)  # map->odom (static) + odom->base_link at 1 s
        latest = buffer.lookup_transform("map", "base_link", Time())
        assert latest.header.stamp.to_nsec() >= 1_000_000_000
    finally:
        stop.set()
        thread.join(5)


def test_a_callback_may_wait_for_a_transform_under_a_single_threaded_executor(rclpy) -> None:  # type: ignore[no-untyped-def]
    from services.ros.rclpy.duration import Duration
    from services.ros.rclpy.executors import SingleThreadedExecutor
    from services.ros.rclpy.time import Time

    node = rclpy.create_node("waits_in_callback")
    buffer = Buffer(node=node)
    TransformListener(buffer, node)
    broadcaster = TransformBroadcaster(node)
    seen: list[float] = []

    def on_number(msg: Int32) -> None:  # blocks the only executor thread while the link arrives
        threading.Timer(0.3, lambda: broadcaster.sendTransform(_link("a", "b", msg.data, x=2.0))).start()
        t = buffer.lookup_transform("a", "b", Time(nanoseconds=msg.data), timeout=Duration(seconds=10.0))
        seen.append(t.transform.translation.x)

    node.create_subscription(Int32, "numbers", on_number, 10)
    publisher = node.create_publisher(Int32, "numbers", 10)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    until(lambda: publisher.get_subscription_count() > 0, what="the subscription")
    publisher.publish(Int32(data=5))
    until(lambda: seen == [2.0], timeout_s=15, what="the lookup inside the callback")
    executor.shutdown()


def test_spin_until_future_complete_with_wait_for_transform_async(rclpy) -> None:  # type: ignore[no-untyped-def]
    from services.ros.rclpy.time import Time

    node = rclpy.create_node("async_waiter")
    buffer = Buffer(node=node)
    TransformListener(buffer, node)
    future = buffer.wait_for_transform_async("world", "thing", Time())
    threading.Timer(0.2, lambda: StaticTransformBroadcaster(node).sendTransform(_link("world", "thing", 0, x=3.0))).start()
    rclpy.spin_until_future_complete(node, future, timeout_sec=20)
    assert future.done() and future.result().transform.translation.x == pytest.approx(3.0)


def test_listeners_and_broadcasters_say_which_node_they_need(rclpy) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ROSInitException, match=r"TransformBroadcaster needs a node: in ROS 2 pass yours"):
        TransformBroadcaster()
    with pytest.raises(TypeError, match="TransformListener takes an rclpy Node"):
        TransformListener(Buffer(), "my_node")
    with pytest.raises(TypeError, match="takes a tf2_ros.Buffer first"):
        TransformListener(object(), None)  # type: ignore[arg-type]
    listener = TransformListener(Buffer(), None)  # ROS 2: None makes a node of its own
    assert listener.node is not None and listener.node.get_name().startswith("transform_listener_impl_")
    with pytest.raises(TypeError, match="sendTransform takes a geometry_msgs TransformStamped"):
        TransformBroadcaster(rclpy.create_node("typo")).sendTransform([Header()])
