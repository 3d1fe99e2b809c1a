"""The robot world as a node, over real sockets: the core and `skydeck run sim --world robot`
in subprocesses, driven by raw WebSocket frames and read over HTTP, as any client would.

The tests share one simulator (4x real time: a 20 Hz command stream from this process stays
well inside the 0.5 s watchdog) and reset it where they need the robot at its start.
"""

from __future__ import annotations

import base64
import contextlib
import json
import math
import statistics
import urllib.request
from collections.abc import Iterator

import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from services.runtime.edge.links import stream_url
from services.runtime.wire import MAX_MESSAGE_BYTES
from sim_server.robot.limits import (
    LASER_HEIGHT_M,
    RANGE_MAX_M,
    RANGE_MIN_M,
    ROBOT_RADIUS_M,
    ROOM_HALF_SIZE_M,
    SCAN_BEAMS,
)
from tests.bad_frames import OversizedFrame, bad_payloads, close_of
from tests.sim_server.robot.room import (
    Recorder,
    call,
    clock_s,
    latest,
    stamp_s,
    start_room,
    truth,
    twist_stream,
    wait_for,
    yaw_of,
)
from tests.web_ui.system import System

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(90)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "1", "--speed", "4")
    yield system
    system.stop()


def _reset(room: System) -> None:
    assert call(room, "/simulator/reset")["success"] is True
    wait_for(room, "/simulator/robots", lambda m: math.hypot(m["poses"][0]["position"]["x"], m["poses"][0]["position"]["y"]) < 1e-3)


def test_the_topics_are_the_neato_drivers(room: System) -> None:
    wait_for(room, "/simulator/world", lambda m: True)
    graph = latest(room, "/api/graph")
    types = {topic["name"]: topic["type"] for topic in graph["topics"]}
    expected = {
        "/cmd_vel": "geometry_msgs/msg/Twist", "/scan": "sensor_msgs/msg/LaserScan",
        "/odom": "nav_msgs/msg/Odometry", "/bump": "neato2_interfaces/msg/Bump",
        "/tf": "tf2_msgs/msg/TFMessage", "/tf_static": "tf2_msgs/msg/TFMessage",
        "/clock": "builtin_interfaces/msg/Time", "/simulator/camera": "sensor_msgs/msg/CompressedImage",
        "/simulator/camera/image_raw": "sensor_msgs/msg/Image",
        "/simulator/people": "geometry_msgs/msg/PoseArray", "/simulator/robots": "geometry_msgs/msg/PoseArray",
        "/simulator/obstacles": "visualization_msgs/msg/MarkerArray", "/simulator/world": "ros_workshop/msg/SimWorld",
    }  # fmt: skip
    assert {name: types.get(name) for name in expected} == expected
    assert "/drone/pose" not in types
    simulator = [s["name"] for s in graph["services"] if s["node"] == "/sim" and not s["name"].startswith("/sim/")]
    assert simulator == ["/simulator/reset"]  # besides the node's parameter services
    world = latest(room, "/simulator/world")
    assert (world["world"], world["namespaces"], world["seed"]) == ("robot", ["/"], 1)


def test_each_topic_comes_at_its_rate_in_sim_time(room: System) -> None:
    """/odom, /tf and /clock at 30 Hz (the issue: >= 20), /scan at 5 Hz, /bump with /odom: read
    from the stamps (sim time), so how fast this machine runs the simulator does not matter."""
    with contextlib.ExitStack() as stack:
        heard = {topic: stack.enter_context(Recorder(room, topic)).messages for topic in ("/odom", "/tf", "/clock", "/scan", "/bump")}
        start = clock_s(wait_for(room, "/clock", lambda m: True))
        wait_for(room, "/clock", lambda m: clock_s(m) > start + 2.5)
    stamps = {
        "/odom": [stamp_s(m) for m in heard["/odom"]],
        "/tf": [stamp_s(m["transforms"][0]) for m in heard["/tf"]],
        "/clock": [clock_s(m) for m in heard["/clock"]],
        "/scan": [stamp_s(m) for m in heard["/scan"]],
    }
    periods = {}
    for topic, times in stamps.items():
        gaps = [b - a for a, b in zip(times, times[1:], strict=False)]
        assert len(gaps) >= 4 and min(gaps) > 0, (topic, gaps[:10])
        periods[topic] = statistics.median(gaps)
    assert periods == {
        "/odom": pytest.approx(1 / 30, rel=0.02), "/tf": pytest.approx(1 / 30, rel=0.02),
        "/clock": pytest.approx(1 / 30, rel=0.02), "/scan": pytest.approx(0.2, rel=0.02),
    }  # fmt: skip
    assert len(heard["/bump"]) >= 0.8 * len(heard["/odom"])  # Bump has no stamp: counted


def test_raw_frames_drive_the_robot_and_the_scan_reads_the_true_wall_distance(room: System) -> None:
    _reset(room)
    with twist_stream(room) as command:
        command["x"] = 0.3
        wait_for(room, "/odom", lambda m: m["pose"]["pose"]["position"]["x"] > 1.5)
        command["x"] = 0.0
        stopped = wait_for(room, "/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3)
        # A scan taken after the stop, and the truth at that time.
        scan = wait_for(room, "/scan", lambda m: stamp_s(m) > stamp_s(stopped) + 0.3)
        x, y, yaw = truth(room)
        assert scan["header"]["frame_id"] == "base_laser_link"
        assert len(scan["ranges"]) == SCAN_BEAMS
        assert (scan["range_min"], scan["range_max"], scan["angle_min"]) == (RANGE_MIN_M, RANGE_MAX_M, 0.0)
        assert scan["angle_increment"] == pytest.approx(math.tau / SCAN_BEAMS)
        to_wall = (ROOM_HALF_SIZE_M - x) / math.cos(yaw)  # along the heading, from the laser
        assert scan["ranges"][0] == pytest.approx(to_wall, abs=0.02)
        odom = latest(room, "/odom")
        assert odom["header"]["frame_id"] == "odom" and odom["child_frame_id"] == "base_link"
        position = odom["pose"]["pose"]["position"]
        assert math.hypot(position["x"] - x, position["y"] - y) < 0.02  # odometry: a little drift
        assert abs(math.remainder(yaw_of(odom["pose"]["pose"]["orientation"]) - yaw, math.tau)) < 0.02
        # On into the wall: it stops against it, and the front bumper says so.
        command["x"] = 0.3
        bump = wait_for(room, "/bump", lambda m: m["left_front"] or m["right_front"], timeout_s=30)
        assert not (bump["left_side"] or bump["right_side"])
        command["x"] = 0.0
    x, _, _ = truth(room)
    # Against the wall: within 2 cm (the stop can land a step after the contact, and the body
    # then rests a little off the wall it pushed into).
    assert x == pytest.approx(ROOM_HALF_SIZE_M - ROBOT_RADIUS_M, abs=0.02)


def test_a_twist_that_is_not_finite_is_refused_and_the_robot_stops(room: System) -> None:
    _reset(room)
    with twist_stream(room) as command:
        command["x"] = 0.2
        wait_for(room, "/odom", lambda m: m["twist"]["twist"]["linear"]["x"] > 0.15)
    # JSON has no NaN: a client that writes one anyway has its socket closed with the reason.
    for bad in ('{"linear": {"x": NaN}}', '{"linear": {"x": 1e999}}', '{"angular": {"z": -Infinity}}'):
        with connect(f"{room.ws_url}/cmd_vel?mode=publish") as websocket:
            websocket.send(bad)
            with pytest.raises(ConnectionClosed) as closed:
                websocket.recv(timeout=10)
        assert closed.value.rcvd is not None and closed.value.rcvd.code == 1007
        assert "linear" in closed.value.rcvd.reason or "angular" in closed.value.rcvd.reason
    # No valid command since: the watchdog stops the robot, and the world goes on.
    odom = wait_for(room, "/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3)
    wait_for(room, "/clock", lambda m: clock_s(m) > stamp_s(odom) + 1.0)


def test_tf_places_the_laser_on_the_robot_and_the_odom_frame_in_the_map(room: System) -> None:
    static = latest(room, "/tf_static")
    edges = {(t["header"]["frame_id"], t["child_frame_id"]): t["transform"] for t in static["transforms"]}
    assert set(edges) == {("map", "odom"), ("base_link", "base_laser_link")}
    assert edges[("base_link", "base_laser_link")]["translation"]["z"] == pytest.approx(LASER_HEIGHT_M)
    assert edges[("map", "odom")]["translation"] == {"x": 0.0, "y": 0.0, "z": 0.0}
    tf = wait_for(room, "/tf", lambda m: True)
    (edge,) = tf["transforms"]
    assert (edge["header"]["frame_id"], edge["child_frame_id"]) == ("odom", "base_link")


def test_the_room_its_obstacles_and_the_person_are_published(room: System) -> None:
    world = latest(room, "/simulator/world")
    markers = latest(room, "/simulator/obstacles")["markers"]
    assert sorted(m["ns"] for m in markers) == ["obstacles"] * world["boxes"] + ["walls"] * 4
    assert all(m["header"]["frame_id"] == "map" and m["type"] == 1 for m in markers)  # CUBEs in map
    first = latest(room, "/simulator/people")
    later = wait_for(room, "/simulator/people", lambda m: stamp_s(m) > stamp_s(first) + 1.0)
    a, b = first["poses"][0]["position"], later["poses"][0]["position"]
    assert 0.1 < math.hypot(a["x"] - b["x"], a["y"] - b["y"]) < 0.5  # walking, about 0.25 m/s


def test_reset_builds_the_world_again_with_the_robot_at_its_start(room: System) -> None:
    before = latest(room, "/simulator/world")
    with twist_stream(room) as command:
        command["z"] = 1.0
        wait_for(room, "/odom", lambda m: abs(m["twist"]["twist"]["angular"]["z"]) > 0.5)
    answer = call(room, "/simulator/reset")
    assert answer["success"] is True and "robots at their starts" in answer["message"]
    after = latest(room, "/simulator/world")
    assert after["id"] != before["id"] and after["build"] == before["build"] + 1
    # The latest /odom may still be the one published before the reset: take the next one.
    stale_seq = latest(room, "/odom")["header"]["seq"]
    odom = wait_for(room, "/odom", lambda m: m["header"]["seq"] > stale_seq)
    assert math.hypot(odom["pose"]["pose"]["position"]["x"], odom["pose"]["pose"]["position"]["y"]) < 0.01


def test_the_camera_looks_ahead_of_the_robot(room: System) -> None:
    with connect(f"{room.ws_url}/simulator/camera", max_size=None) as websocket:
        frame = json.loads(websocket.recv(timeout=20))
    assert frame["format"] == "jpeg"
    assert base64.b64decode(frame["data"])[:2] == b"\xff\xd8"


def test_every_bad_frame_on_cmd_vel_is_refused_and_the_simulator_keeps_serving(room: System) -> None:
    default = latest(room, "/api/interfaces/geometry_msgs/msg/Twist")["default"]
    cases: dict[str, tuple[str | bytes | OversizedFrame, int]] = {name: (body.decode(), 1007) for name, body in bad_payloads(default).items()}
    cases["oversized"] = (OversizedFrame(MAX_MESSAGE_BYTES + 1), 1009)
    cases["binary"] = (bytes(range(256)), 1003)
    assert {"NaN", "Infinity", "unknown field", "malformed"} <= set(cases)
    sim = room.processes["sim"].url
    for base in (room.url, sim):
        for case, (payload, expected) in cases.items():
            code, reason = close_of(stream_url(base, "/cmd_vel"), payload)
            assert code == expected, (case, base, code, reason)
    assert latest(room, "/api/graph") and _health(sim)
    odom = wait_for(room, "/odom", lambda m: True)
    assert abs(odom["twist"]["twist"]["linear"]["x"]) < 1e-3  # nothing bad ever drove it


def _health(url: str) -> bool:
    with urllib.request.urlopen(url + "/health", timeout=5) as reply:
        return reply.status == 200
