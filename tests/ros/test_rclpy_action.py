"""rclpy.action in this process against a real core: goal handles, callbacks and their threads,
what rclpy does with a callback that answers wrongly or raises, and the blocking forms."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

from services.runtime.actions import GoalStatusCode, GoalTransitionError
from tests.ros.conftest import until

pytestmark = [pytest.mark.timeout(60)]


def _fibonacci() -> Any:
    from shared_models import get_interface

    return get_interface("example_interfaces/action/Fibonacci")


def _spin(rclpy: Any, node: Any, *, threads: int = 4) -> Any:
    from services.ros.rclpy.executors import MultiThreadedExecutor

    executor = MultiThreadedExecutor(num_threads=threads)
    executor.add_node(node)
    threading.Thread(target=executor.spin, daemon=True).start()
    return executor


def test_a_goal_from_accept_to_result_with_its_handles(rclpy: Any) -> None:
    from services.ros.rclpy.action import (
        ActionClient,
        ActionServer,
        ServerGoalHandle,
        get_action_names_and_types,
    )

    Fibonacci = _fibonacci()
    seen: dict[str, Any] = {}
    release = threading.Event()

    def execute(goal_handle: ServerGoalHandle) -> Any:
        seen["thread"] = threading.current_thread().name
        seen["handle"] = goal_handle
        seen["executing"] = goal_handle.status
        goal_handle.publish_feedback(Fibonacci.Feedback(sequence=[0, 1, 1]))
        release.wait(10)
        goal_handle.succeed()
        return Fibonacci.Result(sequence=[0, 1, 1])

    server_node = rclpy.create_node("fib_server")
    ActionServer(server_node, Fibonacci, "fibonacci", execute)
    _spin(rclpy, server_node)
    client_node = rclpy.create_node("fib_client")
    client = ActionClient(client_node, Fibonacci, "fibonacci")
    _spin(rclpy, client_node)
    assert client.wait_for_server(timeout_sec=10) and client.server_is_ready()

    feedback_threads: list[str] = []
    done_threads: list[str] = []
    future = client.send_goal_async(Fibonacci.Goal(order=2), feedback_callback=lambda m: feedback_threads.append(threading.current_thread().name))
    future.add_done_callback(lambda f: done_threads.append(threading.current_thread().name))
    until(future.done, what="the goal's answer")
    handle = future.result()
    assert handle.accepted and handle.stamp.sec > 0 and bytes(handle.goal_id.uuid) == bytes(seen["handle"].goal_id.uuid)
    until(lambda: handle.status == GoalStatusCode.EXECUTING, what="the status to reach the client")
    assert seen["executing"] == GoalStatusCode.EXECUTING and seen["handle"].is_active
    until(lambda: len(feedback_threads) == 1, what="the feedback")
    release.set()
    response = handle.get_result()
    assert (response.status, response.result.sequence) == (GoalStatusCode.SUCCEEDED, [0, 1, 1])
    assert handle.status == GoalStatusCode.SUCCEEDED and not seen["handle"].is_active
    # Callbacks ran in the executors' threads, never on the bridge's loop.
    assert all("executor" in name for name in [seen["thread"], *feedback_threads, *done_threads]), (seen, feedback_threads)
    # rclpy lists every action of the graph, the core's tf2_web_republisher (for roslibjs) too
    assert get_action_names_and_types(client_node) == [
        ("/fibonacci", ["example_interfaces/action/Fibonacci"]),
        ("/tf2_web_republisher", ["tf2_web_republisher_interfaces/action/TFSubscription"]),
    ]


def test_wrong_answers_and_errors_in_callbacks_refuse_or_abort(rclpy: Any, caplog: pytest.LogCaptureFixture) -> None:
    from services.ros.rclpy.action import ActionClient, ActionServer

    Fibonacci = _fibonacci()

    def goal_callback(goal: Any) -> Any:
        if goal.order == 1:
            return True  # not a GoalResponse: rclpy refuses the goal with a warning
        if goal.order == 2:
            raise ValueError("no twos")
        return __import__("services.ros.rclpy.action", fromlist=["GoalResponse"]).GoalResponse.ACCEPT

    def execute(goal_handle: Any) -> Any:
        if goal_handle.request.order == 3:
            raise RuntimeError("broken execute")
        if goal_handle.request.order == 4:
            with pytest.raises(GoalTransitionError, match="from state EXECUTING with event CANCELED"):
                goal_handle.canceled()
            with pytest.raises(TypeError, match="publish_feedback takes Fibonacci_Feedback"):
                goal_handle.publish_feedback(Fibonacci.Result())
            return Fibonacci.Result(sequence=[4])  # returned without succeed(): aborted
        return "not a result"

    node = rclpy.create_node("picky")
    ActionServer(node, Fibonacci, "picky", execute, goal_callback=goal_callback)
    client = ActionClient(node, Fibonacci, "picky")
    _spin(rclpy, node)
    assert client.wait_for_server(timeout_sec=10)
    assert client.send_goal(Fibonacci.Goal(order=1)) is None
    assert client.send_goal(Fibonacci.Goal(order=2)) is None
    broken = client.send_goal(Fibonacci.Goal(order=3))
    assert broken.status == GoalStatusCode.ABORTED and broken.result.sequence == []
    unfinished = client.send_goal(Fibonacci.Goal(order=4))
    assert unfinished.status == GoalStatusCode.ABORTED and unfinished.result.sequence == [4]
    wrong = client.send_goal(Fibonacci.Goal(order=5))
    assert wrong.status == GoalStatusCode.ABORTED
    with pytest.raises(TypeError, match="takes example_interfaces/action/Fibonacci goals"):
        client.send_goal_async(Fibonacci.Feedback())
    err = caplog.text
    assert "Goal request callback did not return a GoalResponse type. Rejecting goal." in err
    assert "ValueError: no twos" in err and "RuntimeError: broken execute" in err
    assert "Goal state not set, assuming aborted" in err
    assert "returned str, not Fibonacci_Result" in err


def test_cancel_refused_by_default_and_accepted_with_a_callback(rclpy: Any) -> None:
    from services.ros.rclpy.action import ActionClient, ActionServer, CancelResponse

    Fibonacci = _fibonacci()
    codes = __import__("shared_models").get_interface("action_msgs/srv/CancelGoal").Response

    stop = threading.Event()

    def execute(goal_handle: Any) -> Any:
        while not goal_handle.is_cancel_requested and not stop.is_set():
            time.sleep(0.01)
        goal_handle.canceled() if goal_handle.is_cancel_requested else goal_handle.abort()
        return Fibonacci.Result(sequence=[1])

    node = rclpy.create_node("cancels")
    stubborn = ActionServer(node, Fibonacci, "stubborn", execute)  # rclpy's default: refuse cancels
    ActionServer(node, Fibonacci, "willing", execute, cancel_callback=lambda handle: CancelResponse.ACCEPT)
    _spin(rclpy, node)
    for name, expected in (("stubborn", codes.ERROR_REJECTED), ("willing", codes.ERROR_NONE)):
        client = ActionClient(node, Fibonacci, name)
        assert client.wait_for_server(timeout_sec=10)
        handle = client.send_goal_async(Fibonacci.Goal(order=9))
        until(handle.done, what="the answer")
        goal = handle.result()
        until(lambda goal=goal: goal.status == GoalStatusCode.EXECUTING, what="executing")
        response = goal.cancel_goal()
        assert response.return_code == expected, name
        if name == "willing":
            result = goal.get_result()
            assert (result.status, result.result.sequence) == (GoalStatusCode.CANCELED, [1])
    assert stubborn.action_name == "/stubborn"
    stop.set()  # the stubborn goal still runs


def test_a_single_threaded_executor_runs_one_execute_at_a_time(rclpy: Any) -> None:
    from services.ros.rclpy.action import ActionClient, ActionServer
    from services.ros.rclpy.executors import SingleThreadedExecutor

    Fibonacci = _fibonacci()
    running: list[int] = []
    overlap: list[bool] = []

    def execute(goal_handle: Any) -> Any:
        running.append(goal_handle.request.order)
        overlap.append(len(running) > 1)
        time.sleep(0.2)
        running.remove(goal_handle.request.order)
        goal_handle.succeed()
        return Fibonacci.Result(sequence=[goal_handle.request.order])

    server_node = rclpy.create_node("one_at_a_time")
    ActionServer(server_node, Fibonacci, "serial", execute)
    executor = SingleThreadedExecutor()
    executor.add_node(server_node)
    threading.Thread(target=executor.spin, daemon=True).start()
    client_node = rclpy.create_node("serial_client")
    client = ActionClient(client_node, Fibonacci, "serial")
    assert client.wait_for_server(timeout_sec=10)
    futures = [client.send_goal_async(Fibonacci.Goal(order=n)) for n in (1, 2)]
    for future in futures:
        until(future.done, what="answers")
    results = [future.result().get_result() for future in futures]
    assert [r.result.sequence for r in results] == [[1], [2]] and overlap == [False, False]
