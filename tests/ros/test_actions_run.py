"""A Fibonacci action as a course runs it: servers and clients are user files started by
``skydeck run`` against a real core, ROS 2's (rclpy.action) and ROS 1's (actionlib); what they
print is checked: the feedback sequence, the result, a cancel mid-way, two goals at once, a
refused goal."""

from __future__ import annotations

import re
from collections.abc import Iterator

import pytest

from services.launch.background import BackgroundProcess
from tests.ros.conftest import CORPUS, ros_file
from tests.web_ui.system import System

pytestmark = [pytest.mark.timeout(120)]

ROS2 = CORPUS / "ros2"
ROS1 = CORPUS / "ros1"
FIBONACCI = [0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233]


@pytest.fixture(scope="module")
def ros2_server(core: System) -> Iterator[BackgroundProcess]:
    with ros_file(core, ROS2 / "fibonacci_action_server.py", "--ros-args", "-p", "step:=0.1", sim_time=False) as server:
        server.wait_for_line("/fibonacci_action_server registered", 30)
        yield server


@pytest.fixture(scope="module")
def ros1_server(core: System) -> Iterator[BackgroundProcess]:
    with ros_file(core, ROS1 / "fibonacci_server.py", "_rate:=20", sim_time=False) as server:
        server.wait_for_line("/fibonacci registered", 30)
        yield server


def _lists(lines: list[str], prefix: str) -> list[list[int]]:
    found = []
    for line in lines:
        match = re.search(re.escape(prefix) + r"\s*\[([0-9, ]*)\]", line)
        if match:
            found.append([int(n) for n in match.group(1).split(",") if n.strip()])
    return found


def _finished(client: BackgroundProcess, timeout_s: float = 60) -> list[str]:
    client.popen.wait(timeout_s)
    client.stop()
    assert client.returncode == 0, client.tail()
    return client.lines


def test_feedback_then_the_result(core: System, ros2_server: BackgroundProcess) -> None:
    with ros_file(core, ROS2 / "fibonacci_action_client.py", "5", sim_time=False) as client:
        lines = _finished(client)
    assert any("Goal accepted :)" in line for line in lines)
    assert _lists(lines, "Received feedback:") == [FIBONACCI[: n + 1] for n in range(2, 6)]
    assert _lists(lines, "Result:") == [FIBONACCI[:6]] and any("(status 4)" in line for line in lines)


def test_a_refused_goal(core: System, ros2_server: BackgroundProcess) -> None:
    with ros_file(core, ROS2 / "fibonacci_action_client.py", "-3", sim_time=False) as client:
        lines = _finished(client)
    assert any("Goal rejected :(" in line for line in lines) and not _lists(lines, "Received feedback:")
    ros2_server.wait_for_line("Rejecting goal request (order -3)", 10)


def test_a_goal_cancelled_mid_way(core: System, ros2_server: BackgroundProcess) -> None:
    with ros_file(core, ROS2 / "fibonacci_cancel_client.py", sim_time=False) as client:
        lines = _finished(client)
    feedback = _lists(lines, "Received feedback:")
    result = _lists(lines, "Goal canceled with result:")
    assert any("Goal successfully canceled" in line for line in lines), "\n".join(lines)
    assert len(result) == 1 and 3 <= len(result[0]) < 41  # stopped well before its order of 40
    assert feedback and feedback[-1] == result[0][: len(feedback[-1])]
    ros2_server.wait_for_line("Goal canceled", 10)


def test_two_goals_at_once(core: System, ros2_server: BackgroundProcess) -> None:
    start = len(ros2_server.lines)
    with ros_file(core, ROS2 / "fibonacci_two_goals.py", sim_time=False) as client:
        lines = _finished(client)
    assert _lists(lines, "goal 5 result:") == [FIBONACCI[:6]] and _lists(lines, "goal 7 result:") == [FIBONACCI[:8]]
    assert any("status 4 feedback 4:" in line for line in lines if "goal 5" in line)
    assert any("status 4 feedback 6:" in line for line in lines if "goal 7" in line)
    # The MultiThreadedExecutor ran both: the second started before the first returned.
    server = ros2_server.lines[start:]
    executing = [i for i, line in enumerate(server) if "Executing goal..." in line]
    returning = [i for i, line in enumerate(server) if "Returning result" in line]
    assert len(executing) == 2 and executing[1] < returning[0], "\n".join(server)


def test_ros1_simple_action_server_and_client(core: System, ros1_server: BackgroundProcess) -> None:
    with ros_file(core, ROS1 / "fibonacci_client.py", "6", sim_time=False) as client:
        lines = _finished(client)
    assert lines.index(next(line for line in lines if line == "active")) < lines.index(next(line for line in lines if line.startswith("feedback:")))
    assert _lists(lines, "feedback:") == [FIBONACCI[: n + 1] for n in range(2, 7)]
    assert "done: state 3" in lines and "state: SUCCEEDED" in lines
    assert "Result: 0, 1, 1, 2, 3, 5, 8" in lines


def test_ros1_cancel_preempts_the_goal(core: System, ros1_server: BackgroundProcess) -> None:
    with ros_file(core, ROS1 / "fibonacci_client.py", "30", "_cancel_after:=2", sim_time=False) as client:
        lines = _finished(client)
    assert "done: state 2" in lines and "state: PREEMPTED" in lines
    assert 2 <= len(_lists(lines, "feedback:")) < 29
    ros1_server.wait_for_line("/fibonacci: Preempted", 10)
