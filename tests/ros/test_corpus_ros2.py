"""The ROS 2 corpus (tests/ros/corpus/ros2/: the class's files, written for real rclpy) run
unchanged by ``skydeck run FILE.py`` against a real core and the robot world, each outcome
measured from the simulator's truth or the messages themselves, never assumed."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from collections.abc import Callable, Iterator

import pytest

from sim_server.robot.limits import ROBOT_RADIUS_M, ROOM_HALF_SIZE_M
from tests.ros.conftest import CORPUS, no_skydeck_frames, ros_file
from tests.sim_server.robot.room import (
    Recorder,
    reset_room,
    stamp_s,
    start_room,
    truth,
    wait_for,
)
from tests.web_ui.system import REPO, System

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(240)]

ROS2 = CORPUS / "ros2"


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "1", "--speed", "4")
    yield system
    system.stop()


@pytest.fixture
def fresh(room: System) -> System:
    """The room with its robot back at the start, standing still."""
    return reset_room(room)


def _xy(pose: dict) -> tuple[float, float]:
    return pose["position"]["x"], pose["position"]["y"]


def _still(system: System) -> dict:
    return wait_for(system, "/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3, timeout_s=60)


def _sim_seconds_later(system: System, seconds: float) -> None:
    start = stamp_s(wait_for(system, "/odom", lambda m: True))
    wait_for(system, "/odom", lambda m: stamp_s(m) > start + seconds, timeout_s=60)


HEADER = "std_msgs.msg.Header("


def test_the_seeds_sender_and_receiver_talk(room: System) -> None:
    with (
        ros_file(room, ROS2 / "send_message.py", sim_time=False) as sender,
        ros_file(room, ROS2 / "receive_message.py", sim_time=False) as receiver,
    ):
        receiver.wait_for_line(_nth(11, lambda line: line.startswith(HEADER)), 60)
        sender.wait_for_line("point=geometry_msgs.msg.Point(x=1.0, y=2.0, z=0.0))", 10)
    # print(msg.header) prints rclpy's repr: std_msgs.msg.Header(seq=..., stamp=..., frame_id='odom')
    headers = [line for line in receiver.lines if line.startswith(HEADER)]
    assert len(headers) >= 11 and all(line.endswith("frame_id='odom')") for line in headers)
    seqs = [int(re.search(r"seq=(\d+)", line).group(1)) for line in headers]  # type: ignore[union-attr]
    assert seqs == sorted(seqs) and len(set(seqs)) == len(seqs)  # in order, none twice


def test_the_seeds_skeleton_prints_ten_times_a_second(room: System) -> None:
    with ros_file(room, ROS2 / "send_message_skeleton.py", sim_time=False) as node:
        node.wait_for_line(_nth(10, lambda line: line == "Hi from in_class_day02."), 60)
    assert sum(line == "Hi from in_class_day02." for line in node.lines) >= 10


def test_the_seeds_receive_skeleton_and_plain_main_run(room: System) -> None:
    with ros_file(room, ROS2 / "receive_message_skeleton.py", sim_time=False) as node:
        node.wait_for_line("registered with core", 60)
        graph = json.loads(_get(room, "/api/graph"))
        assert "/receive_message_node" in {n["name"] for n in graph["nodes"]}
    result = subprocess.run(
        [sys.executable, "-m", "services.cli", "run", str(ROS2 / "hello.py")],
        cwd=REPO, capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert result.returncode == 0 and result.stdout == "Hi from in_class_day02.\n"


def _nth(count: int, wanted: Callable[[str], bool]) -> Callable[[str], bool]:
    """A line predicate true from the ``count``-th line on that is ``wanted`` (each line seen once)."""
    seen = [0]

    def predicate(line: str) -> bool:
        seen[0] += wanted(line)
        return seen[0] >= count

    return predicate


def _get(system: System, path: str) -> str:
    import urllib.request

    with urllib.request.urlopen(system.url + path, timeout=5) as reply:
        return reply.read().decode()


@pytest.mark.parametrize("distance", [0.5, 1.0])
def test_wall_stop_stops_at_the_asked_distance(fresh: System, distance: float) -> None:
    with ros_file(fresh, ROS2 / "wall_stop.py", "--ros-args", "-p", f"distance:={distance}") as node:
        node.wait_for_line("stopped: the wall is", 120)
        _still(fresh)
        _sim_seconds_later(fresh, 1.0)
        x, y, _ = truth(fresh)
    ahead = ROOM_HALF_SIZE_M - x  # from the laser (at the robot's centre) to the +x wall
    print(f"wall_stop asked {distance} m, stopped {ahead:.3f} m from the wall")
    assert distance - 0.08 <= ahead <= distance + 0.02, ahead
    assert abs(y) < 0.05


def test_bump_stop_stops_against_the_wall_and_stays(fresh: System) -> None:
    with Recorder(fresh, "/bump") as bumps, ros_file(fresh, ROS2 / "bump_stop.py") as node:
        node.wait_for_line("bumped: stopping", 150)
        _still(fresh)
        x_stopped = truth(fresh)[0]
        _sim_seconds_later(fresh, 2.0)
        x_later = truth(fresh)[0]
    assert any(b["left_front"] or b["right_front"] for b in bumps.messages)
    assert ROOM_HALF_SIZE_M - x_stopped - ROBOT_RADIUS_M < 0.05  # touching the wall
    assert abs(x_later - x_stopped) < 0.01  # and it stayed stopped
    assert not any("Traceback" in line for line in node.lines)


def test_timed_square_with_duration_arithmetic_closes(fresh: System) -> None:
    with Recorder(fresh, "/simulator/robots") as robots, ros_file(fresh, ROS2 / "timed_square.py") as node:
        node.wait_for_line("square done", 200)
        _still(fresh)
        assert node.popen.wait(10) == 0, node.tail()  # the program ended by itself
    x, y, _ = truth(fresh)
    track = [_xy(m["poses"][0]) for m in robots.messages]
    for corner in ((1.0, 0.0), (1.0, 1.0), (0.0, 1.0)):  # it went round a 1 m square
        assert min(math.dist(p, corner) for p in track) < 0.25, corner
    print(f"timed_square closed within {math.hypot(x, y):.3f} m")
    assert math.hypot(x, y) < 0.3, (x, y)  # and closed it, by the clock alone


def test_parameter_driven_node_set_by_ros_args_and_skydeck_param(fresh: System) -> None:
    def speed_settles_at(value: float) -> None:
        wait_for(fresh, "/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"] - value) < 0.01, timeout_s=60)

    def param(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-m", "services.cli", "param", *args],
            cwd=REPO, capture_output=True, text=True, timeout=30,
            env={**__import__("os").environ, "SKYDECK_CORE_URL": fresh.url},
        )  # fmt: skip

    with ros_file(fresh, ROS2 / "param_driver.py", "--ros-args", "-p", "speed:=0.15") as node:
        node.wait_for_line("registered with core", 60)
        speed_settles_at(0.15)
        assert param("get", "/param_driver", "speed").stdout.strip() == "Double value is: 0.15"
        changed = param("set", "/param_driver", "speed", "0.25")
        assert changed.returncode == 0, changed.stderr
        node.wait_for_line("speed is now 0.25", 30)
        speed_settles_at(0.25)
        refused = param("set", "/param_driver", "speed", "5.0")
        assert refused.returncode == 1 and "speed must be between 0 and 0.3 m/s" in refused.stderr + refused.stdout
        assert param("get", "/param_driver", "speed").stdout.strip() == "Double value is: 0.25"
        speed_settles_at(0.25)


def test_service_client_calls_the_simulators_reset(room: System) -> None:
    with ros_file(room, ROS2 / "reset_client.py", sim_time=False) as node:
        node.wait_for_line("reset answered: success=True", 60)
        assert node.popen.wait(20) == 0, node.tail()


def test_callback_exception_shows_the_users_line_and_the_node_keeps_running(room: System) -> None:
    with ros_file(room, ROS2 / "callback_error.py") as node:
        node.wait_for_line("IndexError: list index out of range", 60)
        node.wait_for_line(lambda line: line.startswith("still running") and not line.startswith("still running, 0 "), 30)
        scans_then = _scans(node.lines)
        node.wait_for_line(lambda line: line.startswith("still running") and _scans([line]) > scans_then, 30)
    text = "\n".join(node.lines)
    assert "the subscription callback of /scan raised (the node keeps running)" in text
    assert f'File "{ROS2 / "callback_error.py"}", line 17, in process_scan' in text
    assert "print(msg.ranges[400])" in text
    assert no_skydeck_frames(node.lines), text
    assert text.count("IndexError: list index out of range") == 1  # once: the later scans are fine


def _scans(lines: list[str]) -> int:
    return max(int(line.split(", ")[1].split()[0]) for line in lines if line.startswith("still running"))
