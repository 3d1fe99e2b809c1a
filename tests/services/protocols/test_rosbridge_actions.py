"""Actions through rosbridge: ROS 2's ops (send_action_goal, cancel_action_goal, action_feedback,
action_result) raw and from roslibpy's ActionClient, against a course's rclpy ActionServer; and
ROS 1's actionlib from roslibpy's actionlib client, over topics, against a rospy
SimpleActionServer. The servers are user files run by ``skydeck run``."""

from __future__ import annotations

import asyncio
import os
import sys
from collections.abc import AsyncIterator
from pathlib import Path

import pytest
from websockets.asyncio.client import connect

from services.launch.background import BackgroundProcess
from tests.services.protocols.conftest import Bridge
from tests.services.protocols.test_rosbridge import receive, send

pytestmark = pytest.mark.timeout(90)

CORPUS = Path(__file__).resolve().parents[2] / "ros" / "corpus"
REPO = Path(__file__).resolve().parents[3]
FIBONACCI = [0, 1, 1, 2, 3, 5, 8, 13, 21, 34]
ACTION = {"action": "/fibonacci", "action_type": "example_interfaces/action/Fibonacci"}


async def _run_server(bridge: Bridge, path: Path, *args: str, registered: str) -> AsyncIterator[BackgroundProcess]:
    server = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "run", str(path), *args], name=f"skydeck run {path.name}", cwd=REPO,
        env={**os.environ, "SKYDECK_CORE_URL": bridge.core_url, "SKYDECK_TOKEN": bridge.token, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    try:
        await server.await_line(registered, 30)
        yield server
    finally:
        await asyncio.to_thread(server.stop)


@pytest.fixture
async def ros2_server(bridge: Bridge) -> AsyncIterator[BackgroundProcess]:
    async for server in _run_server(bridge, CORPUS / "ros2" / "fibonacci_action_server.py", "--ros-args", "-p",
                                    "step:=0.1", registered="/fibonacci_action_server registered"):  # fmt: skip
        yield server


@pytest.fixture
async def ros1_server(bridge: Bridge) -> AsyncIterator[BackgroundProcess]:
    async for server in _run_server(bridge, CORPUS / "ros1" / "fibonacci_server.py", "_rate:=20",
                                    registered="/fibonacci registered"):  # fmt: skip
        yield server


async def test_send_action_goal_with_feedback_then_the_result(bridge: Bridge, ros2_server: BackgroundProcess) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="send_action_goal", id="g1", args={"order": 5}, feedback=True, **ACTION)
        feedback = [await receive(ws, "action_feedback", id="g1") for _ in range(4)]
        result = await receive(ws, "action_result", id="g1")
        await send(ws, op="send_action_goal", id="g2", args=[3], **ACTION)  # args in field order; no feedback
        quiet = await receive(ws, "action_result", id="g2")
    assert [f["values"] for f in feedback] == [{"sequence": FIBONACCI[: n + 1]} for n in range(2, 6)]
    assert all(f["action"] == "/fibonacci" for f in feedback)
    assert result == {"op": "action_result", "action": "/fibonacci", "values": {"sequence": FIBONACCI[:6]},
                      "status": 4, "result": True, "id": "g1"}  # fmt: skip
    assert quiet["values"] == {"sequence": FIBONACCI[:4]} and quiet["status"] == 4


async def test_two_goals_at_once_and_one_cancelled(bridge: Bridge, ros2_server: BackgroundProcess) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="send_action_goal", id="long", args={"order": 40}, feedback=True, **ACTION)
        await send(ws, op="send_action_goal", id="short", args={"order": 4}, **ACTION)
        await receive(ws, "action_feedback", id="long")
        await receive(ws, "action_feedback", id="long")
        short = await receive(ws, "action_result", id="short", timeout_s=20)
        await send(ws, op="cancel_action_goal", id="long", action="/fibonacci")
        cancelled = await receive(ws, "action_result", id="long", timeout_s=20)
    assert short["values"] == {"sequence": FIBONACCI[:5]} and short["status"] == 4
    assert cancelled["result"] is True and cancelled["status"] == 5  # CANCELED, its result with it
    assert 3 <= len(cancelled["values"]["sequence"]) < 41
    await ros2_server.await_line("Goal canceled", 10)


async def test_goals_that_cannot_run_end_with_result_false(bridge: Bridge, ros2_server: BackgroundProcess) -> None:
    cases = {
        "refused": ({"args": {"order": 0}, **ACTION}, "Action goal was rejected"),
        "no_server": ({"action": "/nobody", "action_type": ACTION["action_type"]}, "No action server available"),
        "not_action": ({"action": "/fibonacci", "action_type": "std_srvs/srv/Trigger"}, "std_srvs/srv/Trigger is not an action type"),
        "unknown": ({"action": "/fibonacci", "action_type": "example_interfaces/action/Fibonaci"}, "Fibonaci"),
        "bad_args": ({"args": {"order": "five"}, **ACTION}, "args do not fit example_interfaces/action/Fibonacci_Goal: order"),
        "too_many": ({"args": [1, 2], **ACTION}, "2 args for 1 goal fields (order)"),
    }  # fmt: skip
    async with connect(bridge.rosbridge_url) as ws:
        for goal_id, (fields, _) in cases.items():
            await send(ws, op="send_action_goal", id=goal_id, **fields)
        answers: dict[str, dict[str, object]] = {}
        while len(answers) < len(cases):  # in the order they end
            answer = await receive(ws, "action_result")
            answers[str(answer["id"])] = answer
        for goal_id, (_, reason) in cases.items():
            answer = answers[goal_id]
            assert answer["result"] is False and answer["status"] == 0 and reason in str(answer["values"]), (goal_id, answer)
        # Ops that cannot be taken at all: a status error for that op, the connection carries on.
        await send(ws, op="cancel_action_goal", id="never_sent", action="/fibonacci")
        assert "no goal with id 'never_sent'" in (await receive(ws, "status", id="never_sent"))["msg"]
        await send(ws, op="send_action_goal", id="x", action="/fibonacci")  # no action_type
        assert "send_action_goal: action_type: Field required" in (await receive(ws, "status", id="x"))["msg"]
        await send(ws, op="send_action_goal", id="twice", args={"order": 30}, **ACTION)
        await send(ws, op="send_action_goal", id="twice", args={"order": 3}, **ACTION)
        assert "a goal with id 'twice' is in flight" in (await receive(ws, "status", id="twice"))["msg"]
        await send(ws, op="cancel_action_goal", id="twice", action="/fibonacci")
        assert (await receive(ws, "action_result", id="twice"))["status"] == 5


async def test_a_goal_needs_the_write_token(locked_bridge: Bridge) -> None:
    async for _ in _run_server(locked_bridge, CORPUS / "ros2" / "fibonacci_action_server.py", "--ros-args", "-p",
                               "step:=0.1", registered="/fibonacci_action_server registered"):  # fmt: skip
        async with connect(locked_bridge.rosbridge_url) as ws:
            await send(ws, op="send_action_goal", id="g", args={"order": 2}, **ACTION)
            refused = await receive(ws, "action_result", id="g")
        async with connect(locked_bridge.rosbridge_url + "/?token=secret") as ws:
            await send(ws, op="send_action_goal", id="g", args={"order": 2}, **ACTION)
            allowed = await receive(ws, "action_result", id="g")
    assert refused["result"] is False and "token" in refused["values"]
    assert allowed["result"] is True and allowed["values"] == {"sequence": FIBONACCI[:3]}


async def test_the_connection_is_an_action_client_in_the_graph(bridge: Bridge, ros2_server: BackgroundProcess) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="send_action_goal", id="g", args={"order": 30}, feedback=True, **ACTION)
        await receive(ws, "action_feedback", id="g")
        graph = bridge.core.registry.graph()
        feedback = next(t for t in graph["topics"] if t["name"] == "/fibonacci/_action/feedback")
        assert any(name.startswith("/rosbridge_client_") for name in feedback["subscribers"])
        await send(ws, op="cancel_action_goal", id="g", action="/fibonacci")
        await receive(ws, "action_result", id="g")


async def test_roslibpys_ros2_action_client(bridge: Bridge, ros2_server: BackgroundProcess) -> None:
    client = await bridge.client("roslibpy_actions.py", bridge.rosbridge_url, "ros2")
    assert (await client.line())["connected"] is True
    done = await client.expect("result", timeout_s=30)
    assert done["result"] == {"sequence": FIBONACCI[:6]} and done["status"] == "SUCCEEDED"
    assert done["feedback"] == [FIBONACCI[: n + 1] for n in range(2, 6)]
    assert "Traceback" not in await client.finish()
    cancelling = await bridge.client("roslibpy_actions.py", bridge.rosbridge_url, "ros2_cancel")
    ended = await cancelling.expect("result", timeout_s=30)
    assert ended["status"] == "CANCELED" and len(ended["feedback"]) >= 2
    await cancelling.finish()


async def test_roslibpys_actionlib_client_against_a_rospy_simple_action_server(
    bridge: Bridge, ros1_server: BackgroundProcess
) -> None:
    client = await bridge.client("roslibpy_actions.py", bridge.rosbridge_url, "actionlib")
    assert (await client.line())["connected"] is True
    done = await client.expect("result", timeout_s=30)
    assert done["result"] == {"sequence": FIBONACCI[:6]} and done["status"] == 3  # SUCCEEDED
    assert done["feedback"] == [FIBONACCI[: n + 1] for n in range(2, 6)]
    assert 1 in done["statuses"]  # ACTIVE on the way
    assert "Traceback" not in await client.finish()
    cancelling = await bridge.client("roslibpy_actions.py", bridge.rosbridge_url, "actionlib_cancel")
    ended = await cancelling.expect("result", timeout_s=30)
    assert ended["status"] == 2 and ended["result"] == {"sequence": []}  # PREEMPTED, the default result
    await cancelling.finish()
    await ros1_server.await_line("/fibonacci: Preempted", 10)


async def test_ros1_time_fields_are_taken_as_ros2s(bridge: Bridge) -> None:
    """roslibpy's and roslibjs's actionlib stamp a goal {secs, nsecs}, ROS 1's names."""
    async with connect(bridge.rosbridge_url) as reader, connect(bridge.rosbridge_url) as writer:
        await send(reader, op="set_level", level="info")
        await send(reader, op="subscribe", topic="/stamped_header", type="std_msgs/Header", id="s")
        await receive(reader, "status", id="s")  # reading from now on
        await send(writer, op="advertise", topic="/stamped_header", type="std_msgs/Header")
        await send(writer, op="publish", topic="/stamped_header", msg={"stamp": {"secs": 3, "nsecs": 5}, "frame_id": "odom"}, id="p")
        got = await receive(reader, "publish")
    assert got["msg"]["stamp"] == {"sec": 3, "nanosec": 5} and got["msg"]["frame_id"] == "odom"


async def test_ros1s_actionlib_types_go_out_with_ros1s_time_names_too(bridge: Bridge) -> None:
    """roslibpy's SimpleActionServer reads a cancel's ``stamp["secs"]``: a type of ROS 1's
    actionlib is sent with both names; a client echoing both is taken as ROS 2's; other types
    are sent as they are."""
    async with connect(bridge.rosbridge_url) as reader, connect(bridge.rosbridge_url) as writer:
        await send(reader, op="set_level", level="info")
        for topic, type_name in (("/act/cancel", "actionlib_msgs/GoalID"), ("/act/stamped", "std_msgs/Header")):
            await send(reader, op="subscribe", topic=topic, type=type_name, id=topic)
            await receive(reader, "status", id=topic)
            await send(writer, op="advertise", topic=topic, type=type_name)
        both = {"sec": 3, "nanosec": 5, "secs": 3, "nsecs": 5}
        await send(writer, op="publish", topic="/act/cancel", msg={"stamp": {"secs": 3, "nsecs": 5}, "id": "g1"})
        assert (await receive(reader, "publish", topic="/act/cancel"))["msg"] == {"stamp": both, "id": "g1"}
        await send(writer, op="publish", topic="/act/cancel", msg={"stamp": both, "id": "g2"}, id="echo")
        assert (await receive(reader, "publish", topic="/act/cancel"))["msg"] == {"stamp": both, "id": "g2"}
        await send(writer, op="publish", topic="/act/stamped", msg={"stamp": {"secs": 3, "nsecs": 5}, "frame_id": "odom"})
        stamped = (await receive(reader, "publish", topic="/act/stamped"))["msg"]
    assert stamped["stamp"] == {"sec": 3, "nanosec": 5}
