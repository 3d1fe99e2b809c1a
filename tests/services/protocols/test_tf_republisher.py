"""tf2_web_republisher in the core: roslibpy's TFClient (the republish_tfs service and its topic),
roslibjs's TFClient (ROS 1's actionlib action) and ROS2TFClient (ROS 2's action), following a
course-style tf2 broadcaster run by ``skydeck run``; what it refuses; a goal nobody reads; and
the thresholds, on a buffer of our own."""

from __future__ import annotations

import asyncio
import math
from collections.abc import AsyncIterator
from typing import Any

import pytest
from websockets.asyncio.client import connect

from services.launch.background import BackgroundProcess
from services.protocols.rosbridge import tf_republisher
from services.protocols.rosbridge.tf_watch import TFRequest, TFSource, Watch
from shared_models.geometry_msgs import TransformStamped
from tests.conftest import wait_until
from tests.services.protocols.conftest import Bridge
from tests.services.protocols.test_rosbridge import call, receive, send
from tests.services.protocols.test_rosbridge_actions import CORPUS, _run_server

pytestmark = pytest.mark.timeout(90)

GOAL = {"source_frames": ["carrot"], "target_frame": "world", "angular_thres": 0.01, "trans_thres": 0.01, "rate": 20.0}


@pytest.fixture
async def carrot(bridge: Bridge) -> AsyncIterator[BackgroundProcess]:
    async for server in _run_server(bridge, CORPUS / "ros2" / "carrot_broadcaster.py",
                                    registered="/carrot_broadcaster registered"):  # fmt: skip
        yield server


def _on_the_circle(transform: dict[str, Any]) -> bool:
    t = transform["translation"]
    return abs(math.hypot(t["x"], t["y"]) - 1.0) < 1e-6 and t["z"] == 0


def _reads(bridge: Bridge, node: str, topic: str) -> bool:
    found = next((n for n in bridge.core.registry.graph()["nodes"] if n["name"] == node), None)
    return found is not None and topic in found["subscriptions"]


def _topics(bridge: Bridge) -> set[str]:
    return {t["name"] for t in bridge.core.registry.graph()["topics"]}


async def test_roslibpys_tf_client_reads_the_topic_republish_tfs_answers(bridge: Bridge, carrot: BackgroundProcess) -> None:
    client = await bridge.client("roslibpy_client.py", bridge.rosbridge_url, "tf")
    assert (await client.line())["connected"] is True
    got = await client.expect("carrots")
    carrots = got["carrots"]
    assert all(_on_the_circle(c) for c in carrots)
    assert len({(c["translation"]["x"], c["translation"]["y"]) for c in carrots}) == 5  # it moves
    # The post stands still: sent once, at its place.
    assert got["posts"] == [{"translation": {"x": 2.0, "y": 0.0, "z": 0.0}, "rotation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}}]
    assert got["topic"] == "/tf2_web_republisher/tf_repub_0"
    assert "Traceback" not in await client.finish()
    # Unread for the request's timeout (roslibpy's 2 s), the topic goes, and the core reads TF no more.
    await wait_until(lambda: got["topic"] not in _topics(bridge), timeout_s=10, what="the topic to go")
    assert not _reads(bridge, tf_republisher.NODE, "/tf")


@pytest.mark.parametrize("scenario", ["tf_ros1", "tf_ros2"])
async def test_roslibjs_tf_clients_follow_frames_through_either_action(
    bridge: Bridge, carrot: BackgroundProcess, scenario: str
) -> None:
    client = await bridge.client("roslibjs_client.mjs", bridge.rosbridge_url, scenario)
    assert (await client.line())["connected"] is True
    got = await client.expect("carrots")
    assert all(_on_the_circle(c) for c in got["carrots"])
    assert len({(c["translation"]["x"], c["translation"]["y"]) for c in got["carrots"]}) == 5
    assert got["posts"] == [{"translation": {"x": 2, "y": 0, "z": 0}}]
    await client.finish()


async def test_the_actions_are_listed_by_rosapi(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        servers = (await call(ws, "/rosapi/action_servers", "a"))["values"]["action_servers"]
        action_type = (await call(ws, "/rosapi/action_type", "t", args={"action": "/tf2_web_republisher"}))["values"]
    assert "/tf2_web_republisher" in servers  # ROS 2's, and ROS 1's five topics
    assert action_type == {"type": "tf2_web_republisher_interfaces/action/TFSubscription"}


async def test_requests_that_cannot_run_are_refused_each_the_way_its_interface_refuses(bridge: Bridge) -> None:
    async with connect(bridge.rosbridge_url) as ws:
        no_rate = await call(ws, "/republish_tfs", "s", args={**GOAL, "rate": 0.0, "timeout": {"secs": 2, "nsecs": 0}})
        assert no_rate["result"] is False and "rate must be more than 0" in no_rate["values"]
        # ROS 2's action: the goal is not accepted.
        await send(ws, op="send_action_goal", id="g", action="/tf2_web_republisher",
                   action_type="tf2_web_republisher_interfaces/action/TFSubscription", args={**GOAL, "source_frames": []})  # fmt: skip
        refused = await receive(ws, "action_result", id="g")
        assert refused["result"] is False
        # ROS 1's action: the goal is rejected, with why, on the result topic.
        await send(ws, op="subscribe", topic="/tf2_web_republisher/result", type="tf2_web_republisher/TFSubscriptionActionResult")
        await send(ws, op="advertise", topic="/tf2_web_republisher/goal", type="tf2_web_republisher/TFSubscriptionActionGoal")
        await send(ws, op="publish", topic="/tf2_web_republisher/goal",
                   msg={"goal_id": {"stamp": {"secs": 0, "nsecs": 0}, "id": "no_target"}, "goal": {**GOAL, "target_frame": ""}})  # fmt: skip
        result = (await receive(ws, "publish", topic="/tf2_web_republisher/result"))["msg"]
    assert result["status"]["goal_id"]["id"] == "no_target" and result["status"]["status"] == 5  # REJECTED
    assert result["status"]["text"] == "target_frame must name a frame"


async def test_a_ros1_goal_nobody_reads_is_aborted_and_a_cancelled_one_preempted(
    bridge: Bridge, carrot: BackgroundProcess, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(tf_republisher, "UNREAD_GOAL_S", 0.5)
    async with connect(bridge.rosbridge_url) as ws:
        await send(ws, op="subscribe", topic="/tf2_web_republisher/result", type="tf2_web_republisher/TFSubscriptionActionResult")
        await send(ws, op="advertise", topic="/tf2_web_republisher/goal", type="tf2_web_republisher/TFSubscriptionActionGoal")
        await send(ws, op="advertise", topic="/tf2_web_republisher/cancel", type="actionlib_msgs/GoalID")
        goal_id = {"stamp": {"secs": 0, "nsecs": 0}, "id": "unread"}
        await send(ws, op="publish", topic="/tf2_web_republisher/goal", msg={"goal_id": goal_id, "goal": GOAL})
        ended = (await receive(ws, "publish", topic="/tf2_web_republisher/result"))["msg"]["status"]
        assert ended["goal_id"]["id"] == "unread" and ended["status"] == 4  # ABORTED
        assert ended["text"] == "nobody read /tf2_web_republisher/feedback for 0.5 s"
        await send(ws, op="subscribe", topic="/tf2_web_republisher/feedback", type="tf2_web_republisher/TFSubscriptionActionFeedback")
        await send(ws, op="publish", topic="/tf2_web_republisher/goal", msg={"goal_id": {**goal_id, "id": "read"}, "goal": GOAL})
        feedback = (await receive(ws, "publish", topic="/tf2_web_republisher/feedback"))["msg"]
        assert feedback["status"]["goal_id"]["id"] == "read" and feedback["status"]["status"] == 1  # ACTIVE
        assert [t["child_frame_id"] for t in feedback["feedback"]["transforms"]] == ["carrot"]
        await send(ws, op="publish", topic="/tf2_web_republisher/cancel", msg={"id": "read"})
        cancelled = (await receive(ws, "publish", topic="/tf2_web_republisher/result"))["msg"]["status"]
    assert cancelled["goal_id"]["id"] == "read" and cancelled["status"] == 2  # PREEMPTED


class _Host:
    """What a TFSource uses of the core's host, for a watch on a buffer the test fills."""

    access: Any = None

    def create_subscription(self, *args: Any) -> object:
        return object()

    def destroy_subscription(self, tap: object) -> None:
        pass


def _link(x: float, yaw: float) -> TransformStamped:
    link = TransformStamped(child_frame_id="carrot")
    link.header.frame_id = "world"
    link.transform.translation.x = x
    link.transform.rotation.z, link.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return link


async def test_a_frame_is_sent_again_once_it_moved_or_turned_past_its_threshold(monkeypatch: pytest.MonkeyPatch) -> None:
    from services.protocols.rosbridge import tf_watch

    monkeypatch.setattr(tf_watch.clock, "now", lambda access: _link(0, 0).header.stamp)
    source = TFSource(_Host())  # type: ignore[arg-type]
    request = TFRequest(("carrot", "nowhere"), "world", angular_thres=0.1, trans_thres=0.5, rate=0.001)
    watch = Watch(source, request, lambda transforms: None, wanted=lambda: True, unread_s=60, on_abandoned=lambda: None)
    try:
        buffer = source.buffer()

        def moved_to(x: float, yaw: float) -> list[float]:
            buffer.set_transform_static(_link(x, yaw), "test")
            return [t.transform.translation.x for t in watch.moved()]

        assert moved_to(0.0, 0.0) == [0.0]  # the first lookup is sent; "nowhere" is not known
        assert moved_to(0.4, 0.0) == []  # 0.4 m from what was sent
        assert moved_to(0.6, 0.0) == [0.6]  # 0.6 m
        assert moved_to(0.6, 0.15) == []  # tf's angle is half the turn: 0.075
        assert moved_to(0.6, 0.3) == [0.6]  # 0.15
    finally:
        watch.stop()
    assert source._watches == 0
    await asyncio.sleep(0)  # the cancelled task ends
