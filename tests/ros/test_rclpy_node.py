"""The rclpy façade in this process against a real core (a subprocess): publish/subscribe from
threads, services and clients called every way rclpy allows, parameters reaching the on-set
callback from the graph, executors and callback groups, and errors that name themselves."""

from __future__ import annotations

import json
import threading
import time
import urllib.request

import pytest

from services.ros.errors import NotProvidedError
from services.ros.rclpy.context import NotInitializedException
from tests.ros.conftest import until
from tests.web_ui.system import System

pytestmark = [pytest.mark.timeout(60)]


def _spin_in_thread(rclpy, node) -> threading.Thread:  # type: ignore[no-untyped-def]
    thread = threading.Thread(target=rclpy.spin, args=(node,), daemon=True)
    thread.start()
    return thread


def test_a_node_needs_init_first(core: System) -> None:
    from services.ros import rclpy

    with pytest.raises(NotInitializedException, match=r"rclpy.init\(\) must be called before creating a node"):
        rclpy.create_node("too_early")


def test_publishing_from_many_threads_reaches_the_subscriber_in_the_executor(rclpy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_msgs import Int32

    talker = rclpy.create_node("talker")
    listener = rclpy.create_node("listener")
    got: list[tuple[int, str]] = []
    listener.create_subscription(Int32, "numbers", lambda m: got.append((m.data, threading.current_thread().name)), 1000)
    publisher = talker.create_publisher(Int32, "numbers", 1000)
    _spin_in_thread(rclpy, listener)
    until(lambda: publisher.get_subscription_count() > 0, what="the listener to link")
    msg = Int32()
    threads = [threading.Thread(target=lambda k=k: [publisher.publish(Int32(data=k * 100 + i)) for i in range(100)]) for k in range(3)]
    for thread in threads:
        thread.start()
    for i in range(100):  # the same message object, changed after each publish: each copy counts
        msg.data = 300 + i
        publisher.publish(msg)
    for thread in threads:
        thread.join()
    until(lambda: len(got) == 400, what="400 messages")
    assert sorted(n for n, _ in got) == list(range(400))
    assert {name for _, name in got} == {next(t.name for t in threading.enumerate() if t.name == got[0][1])}
    assert "bridge" not in got[0][1]  # callbacks run in the spinning thread, not on the loop
    with pytest.raises(TypeError, match="Expected std_msgs/msg/Int32"):
        publisher.publish("42")


def test_keep_last_depth_drops_the_oldest_while_nobody_spins(rclpy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_msgs import Int32

    node = rclpy.create_node("depth")
    got: list[int] = []
    node.create_subscription(Int32, "burst", lambda m: got.append(m.data), 3)
    publisher = node.create_publisher(Int32, "burst", 100)
    for i in range(10):
        publisher.publish(Int32(data=i))
    time.sleep(0.3)  # delivered into the subscription's queue by the loop, nobody spinning
    for _ in range(5):
        rclpy.spin_once(node, timeout_sec=0.2)
    assert got == [7, 8, 9]


def test_services_answer_calls_from_main_thread_callbacks_and_futures(rclpy) -> None:  # type: ignore[no-untyped-def]
    from shared_models.std_msgs import Empty
    from shared_models.std_srvs import SetBool, Trigger

    server = rclpy.create_node("server")
    state = {"on": False}

    def switch(request, response):  # type: ignore[no-untyped-def]
        state["on"] = request.data
        response.success = True
        response.message = f"now {'on' if request.data else 'off'}"
        return response

    server.create_service(SetBool, "switch", switch)
    _spin_in_thread(rclpy, server)
    client_node = rclpy.create_node("client")
    client = client_node.create_client(SetBool, "switch")
    assert client.wait_for_service(timeout_sec=5.0)
    assert client.call(SetBool.Request(data=True)).message == "now on" and state["on"] is True
    future = client.call_async(SetBool.Request(data=False))
    rclpy.spin_until_future_complete(client_node, future, timeout_sec=5.0)
    assert future.done() and future.result().message == "now off"
    # A blocking call from inside a callback (rclpy would deadlock a single-threaded executor).
    answers: list[str] = []
    client_node.create_subscription(Empty, "poke", lambda m: answers.append(client.call(SetBool.Request(data=True)).message), 10)
    poke = server.create_publisher(Empty, "poke", 10)
    until(lambda: poke.get_subscription_count() > 0, what="poke link")
    poke.publish(Empty())
    for _ in range(50):
        if answers:
            break
        rclpy.spin_once(client_node, timeout_sec=0.1)
    assert answers == ["now on"]
    assert client_node.create_client(Trigger, "nobody_serves_this").wait_for_service(timeout_sec=0.2) is False


def test_a_service_callback_that_raises_answers_500_and_the_node_keeps_serving(rclpy, caplog) -> None:  # type: ignore[no-untyped-def]
    from services.runtime.errors import ServiceCallRejectedError
    from shared_models.std_srvs import Trigger

    server = rclpy.create_node("fragile")
    calls = []

    def handle(request, response):  # type: ignore[no-untyped-def]
        calls.append(1)
        if len(calls) == 1:
            raise RuntimeError("first call fails")
        response.success = True
        return response

    server.create_service(Trigger, "fragile_reset", handle)
    _spin_in_thread(rclpy, server)
    client = server.create_client(Trigger, "fragile_reset")
    assert client.wait_for_service(timeout_sec=5.0)
    with pytest.raises(ServiceCallRejectedError, match="500"):
        client.call(Trigger.Request())
    assert client.call(Trigger.Request()).success is True
    err = caplog.text
    assert "the service callback of /fragile_reset raised (the node keeps running)" in err
    assert 'in handle\n    raise RuntimeError("first call fails")' in err and "services/ros" not in err


def test_parameters_from_overrides_api_and_the_graph_reach_the_on_set_callback(rclpy, core: System) -> None:  # type: ignore[no-untyped-def]
    from services.ros.rclpy.parameter import Parameter
    from shared_models.rcl_interfaces import SetParametersResult

    node = rclpy.create_node("tuned", cli_args=["--ros-args", "-p", "speed:=0.2"])
    assert node.declare_parameter("speed", 0.1).value == 0.2
    seen: list[float] = []

    def check(parameters):  # type: ignore[no-untyped-def]
        for p in parameters:
            if p.name == "speed" and p.value > 0.3:
                return SetParametersResult(successful=False, reason="at most 0.3")
            seen.append(p.value)
        return SetParametersResult(successful=True)

    node.add_on_set_parameters_callback(check)
    results = node.set_parameters([Parameter("speed", Parameter.Type.DOUBLE, 0.9), Parameter("speed", value=0.25)])
    assert [r.successful for r in results] == [False, True] and results[0].reason == "at most 0.3"
    until(lambda: "/tuned" in _node_names(core), what="/tuned to register")  # registration is asynchronous
    body = json.dumps({"parameters": [{"name": "speed", "value": {"type": 3, "double_value": 0.3}}]}).encode()
    request = urllib.request.Request(core.url + "/tuned/set_parameters", data=body, method="POST",
                                     headers={"Content-Type": "application/json"})  # fmt: skip
    with urllib.request.urlopen(request, timeout=10) as reply:
        assert json.loads(reply.read())["results"][0]["successful"] is True
    assert node.get_parameter("speed").value == 0.3 and seen == [0.25, 0.3]


def test_multithreaded_executor_runs_reentrant_callbacks_together_and_exclusive_ones_apart(rclpy) -> None:  # type: ignore[no-untyped-def]
    from services.ros.rclpy.callback_groups import (
        MutuallyExclusiveCallbackGroup,
        ReentrantCallbackGroup,
    )
    from services.ros.rclpy.executors import MultiThreadedExecutor

    node = rclpy.create_node("groups")
    running = {"reentrant": 0, "exclusive": 0}
    most = {"reentrant": 0, "exclusive": 0}
    lock = threading.Lock()

    def slow(kind: str):  # type: ignore[no-untyped-def]
        def callback() -> None:
            with lock:
                running[kind] += 1
                most[kind] = max(most[kind], running[kind])
            time.sleep(0.15)
            with lock:
                running[kind] -= 1

        return callback

    reentrant, exclusive = ReentrantCallbackGroup(), MutuallyExclusiveCallbackGroup()
    for _ in range(3):
        node.create_timer(0.05, slow("reentrant"), callback_group=reentrant)
        node.create_timer(0.05, slow("exclusive"), callback_group=exclusive)
    executor = MultiThreadedExecutor(num_threads=8)
    executor.add_node(node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    time.sleep(1.0)
    executor.shutdown()
    spinner.join(5)
    assert most["reentrant"] >= 2 and most["exclusive"] == 1, most


def test_timer_rate_and_clock_on_the_nodes_time(rclpy) -> None:  # type: ignore[no-untyped-def]
    from services.ros.rclpy.duration import Duration

    node = rclpy.create_node("ticker")
    ticks: list[int] = []
    timer = node.create_timer(0.05, lambda: ticks.append(node.get_clock().now().nanoseconds))
    _spin_in_thread(rclpy, node)
    rate = node.create_rate(20)
    start = node.get_clock().now()
    for _ in range(10):
        rate.sleep()
    elapsed = node.get_clock().now() - start
    assert Duration(seconds=0.45) <= elapsed and len(ticks) >= 5
    timer.cancel()
    count = len(ticks)
    time.sleep(0.2)
    assert len(ticks) <= count + 1 and timer.is_canceled()


def test_destroy_node_ends_spin_and_leaves_the_graph(rclpy, core: System) -> None:  # type: ignore[no-untyped-def]
    node = rclpy.create_node("short_lived", namespace="robot3")
    assert node.get_fully_qualified_name() == "/robot3/short_lived" and node.get_name() == "short_lived"
    spinner = _spin_in_thread(rclpy, node)
    node.destroy_node()
    spinner.join(5)
    assert not spinner.is_alive()
    until(lambda: "/robot3/short_lived" not in _node_names(core), what="the node to leave the graph")


def _node_names(core: System) -> set[str]:
    with urllib.request.urlopen(core.url + "/api/graph", timeout=5) as reply:
        return {n["name"] for n in json.loads(reply.read())["nodes"]}


def test_apis_not_provided_name_themselves(rclpy) -> None:  # type: ignore[no-untyped-def]
    node = rclpy.create_node("asks_too_much")
    with pytest.raises(NotProvidedError, match="Node.create_guard_condition is a ROS API Skydeck does not provide"):
        node.create_guard_condition(lambda: None)
    with pytest.raises(NotProvidedError, match="rclpy.lifecycle is a ROS API"):
        _ = rclpy.lifecycle
    with pytest.raises(AttributeError, match="has no attribute 'not_a_thing'"):
        _ = node.not_a_thing
