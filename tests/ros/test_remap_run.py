"""Remapping and namespaces as a user gives them to ``skydeck run FILE.py``: ROS 2's
``--ros-args -r`` and ROS 1's ``name:=value``, on an unchanged ROS file against a real core."""

from __future__ import annotations

import httpx
import pytest

from tests.conftest import await_registered
from tests.ros.conftest import CORPUS, ros_file

pytestmark = pytest.mark.timeout(90)

SENDER = CORPUS / "ros2" / "send_message.py"  # node send_message_node, publishes my_point


@pytest.mark.parametrize(
    ("args", "node", "topic"),
    [
        (("--ros-args", "-r", "my_point:=/elsewhere", "-r", "__ns:=/robot1", "-r", "__node:=sender"), "/robot1/sender", "/elsewhere"),
        (("my_point:=/elsewhere", "__ns:=/robot1", "__name:=sender"), "/robot1/sender", "/elsewhere"),
        (("--ros-args", "-r", "__ns:=/robot2"), "/robot2/send_message_node", "/robot2/my_point"),
        ((), "/send_message_node", "/my_point"),
    ],
    ids=["ros2 remap, ns and node", "ros1 spelling", "namespace only", "as written"],
)
async def test_skydeck_run_applies_the_names_the_user_gives(core, args, node, topic) -> None:  # type: ignore[no-untyped-def]
    with ros_file(core, SENDER, *args, sim_time=False):
        await await_registered(core.url, {node}, timeout_s=60)
        async with httpx.AsyncClient() as http:
            graph = (await http.get(core.url + "/api/graph", timeout=5)).json()
    publishers = {t["name"]: t["publishers"] for t in graph["topics"]}
    assert node in publishers.get(topic, []), publishers
    spellings = {"/robot1/sender", "/robot2/send_message_node", "/send_message_node", "/robot1/send_message_node"}
    assert {n["name"] for n in graph["nodes"]} & spellings == {node}, "the node is in the graph once, as named"
