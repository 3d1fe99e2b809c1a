"""Several robots (`--robots 2`): each in its namespace, deaf to the other's commands."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

from sim_server.robot.limits import ROBOT_STARTS_M
from tests.sim_server.robot.room import latest, start_room, truth, twist_stream, wait_for
from tests.web_ui.system import System

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(90)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "2", "--speed", "4", "--robots", "2")
    yield system
    system.stop()


def test_each_robot_has_its_topics_and_frames_under_its_namespace(room: System) -> None:
    world = wait_for(room, "/simulator/world", lambda m: True)
    assert world["namespaces"] == ["/robot1", "/robot2"]
    topics = {t["name"] for t in latest(room, "/api/graph")["topics"]}
    for ns in ("/robot1", "/robot2"):
        assert {f"{ns}/cmd_vel", f"{ns}/scan", f"{ns}/odom", f"{ns}/bump"} <= topics
    assert not {"/cmd_vel", "/scan", "/odom", "/bump"} & topics
    odom = wait_for(room, "/robot2/odom", lambda m: True)
    assert (odom["header"]["frame_id"], odom["child_frame_id"]) == ("robot2/odom", "robot2/base_link")
    assert wait_for(room, "/robot1/scan", lambda m: True)["header"]["frame_id"] == "robot1/base_laser_link"
    static = {(t["header"]["frame_id"], t["child_frame_id"]): t["transform"] for t in latest(room, "/tf_static")["transforms"]}
    assert static[("map", "robot2/odom")]["translation"]["y"] == pytest.approx(ROBOT_STARTS_M[1][1])
    assert ("robot1/base_link", "robot1/base_laser_link") in static
    tf = wait_for(room, "/tf", lambda m: True)
    assert {t["child_frame_id"] for t in tf["transforms"]} == {"robot1/base_link", "robot2/base_link"}


def test_robots_do_not_hear_each_others_commands(room: System) -> None:
    with twist_stream(room, "/robot1/cmd_vel") as command:
        command["z"] = 1.5
        wait_for(room, "/robot1/odom", lambda m: abs(m["twist"]["twist"]["angular"]["z"]) > 1.0)
    with twist_stream(room, "/robot2/cmd_vel") as command:
        command["x"] = 0.3
        wait_for(room, "/robot2/odom", lambda m: m["pose"]["pose"]["position"]["x"] > 0.5)
    wait_for(room, "/robot2/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3)
    one, two = truth(room, 0), truth(room, 1)
    assert math.hypot(one[0] - ROBOT_STARTS_M[0][0], one[1] - ROBOT_STARTS_M[0][1]) < 0.01  # turned in place
    assert abs(one[2]) > 0.5
    assert two[0] > ROBOT_STARTS_M[1][0] + 0.5 and abs(two[2]) < 0.05  # drove straight, never turned
    odom_one = latest(room, "/robot1/odom")["pose"]["pose"]["position"]
    assert math.hypot(odom_one["x"], odom_one["y"]) < 0.01  # robot 1's wheels never drove it forward
