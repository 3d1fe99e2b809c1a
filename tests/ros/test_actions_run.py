"""A Fibonacci action as a course runs it: servers and clients are user files started by
``skydeck run`` against a real core, ROS 2's (rclpy.action) and ROS 1's (actionlib); what they
print is checked: the feedback sequence, the result, a cancel mid-way, two goals at once, a
refused goal; and the same through `skydeck action`."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
from collections.abc import Iterator

import pytest

from services.launch.background import BackgroundProcess
from tests.ros.conftest import CORPUS, ros_file
from tests.web_ui.system import REPO, System

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



def test_ros1_goal_callback_mode_and_send_goal_and_wait(core: System) -> None:
    with ros_file(core, ROS1 / "averaging_server.py", "_rate:=40", sim_time=False) as server:
        server.wait_for_line("/averaging registered", 30)
        runs = {}
        for args in (("20",), ("4",), ("400", "0.5")):
            with ros_file(core, ROS1 / "averaging_client.py", *args, sim_time=False) as client:
                runs[args[0]] = _finished(client)
        server.wait_for_line("/averaging: Preempted", 10)
    assert "state: SUCCEEDED" in runs["20"] and "mean: 10.50 std_dev: 5.766 text: " in runs["20"]
    assert "state: ABORTED" in runs["4"] and "mean: 2.50 std_dev: 1.118 text: " in runs["4"]
    # Not done within its 0.5 s: send_goal_and_wait cancels it; the preempt callback ends it.
    assert "state: PREEMPTED" in runs["400"] and "mean: 0.00 std_dev: 0.000 text: " in runs["400"]

# -- the CLI ------------------------------------------------------------------------------------


def _skydeck(system: System, *args: str, timeout_s: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "services.cli", *args], cwd=REPO, capture_output=True, text=True, timeout=timeout_s,
        env={**os.environ, "SKYDECK_CORE_URL": system.url},
    )  # fmt: skip


def test_cli_lists_and_describes_actions(core: System, ros2_server: BackgroundProcess, ros1_server: BackgroundProcess) -> None:
    listed = _skydeck(core, "action", "list")
    every = _skydeck(core, "action", "list", "-a")
    typed = _skydeck(core, "action", "list", "-t")
    info = _skydeck(core, "action", "info", "fibonacci")
    unknown = _skydeck(core, "action", "info", "/nothing_here")
    assert listed.stdout.splitlines() == ["/fibonacci"]  # ROS 1's actionlib topics are no ROS 2 action
    assert typed.stdout.splitlines() == ["/fibonacci [example_interfaces/action/Fibonacci]"]
    assert every.stdout.splitlines() == ["/fibonacci", "/tf2_web_republisher"]  # the core's, for roslibjs's TFClient
    assert info.stdout.splitlines() == [
        "Action: /fibonacci", "Action clients: 0", "Action servers: 1", "    /fibonacci_action_server"]  # fmt: skip
    assert unknown.returncode == 1 and unknown.stderr == "skydeck: error: unknown action /nothing_here: see `skydeck action list`\n"


def test_cli_sends_a_goal_and_prints_feedback_and_result(core: System, ros2_server: BackgroundProcess) -> None:
    done = _skydeck(core, "action", "send_goal", "/fibonacci", "example_interfaces/action/Fibonacci", "{order: 5}", "--feedback")
    assert done.returncode == 0, done.stderr
    text = done.stdout
    assert text.startswith("Waiting for an action server to become available...\nSending goal:\n     order: 5\n\nGoal accepted with ID: ")
    goal_id = text.split("Goal accepted with ID: ")[1].split("\n")[0]
    assert re.fullmatch(r"[0-9a-f]{32}", goal_id)
    feedback = [block.split("Result:")[0] for block in text.split("Feedback:\n")[1:]]
    assert [[int(n) for n in re.findall(r"- (\d+)", block)] for block in feedback] == [FIBONACCI[: n + 1] for n in range(2, 6)]
    assert "Result:\n    sequence:\n- 0\n- 1\n- 1\n- 2\n- 3\n- 5\n\nGoal finished with status: SUCCEEDED\n" in text
    quiet = _skydeck(core, "action", "send_goal", "fibonacci", "example_interfaces/action/Fibonacci", '{"order": 2}')
    assert "Feedback:" not in quiet.stdout and "Goal finished with status: SUCCEEDED" in quiet.stdout
    refused = _skydeck(core, "action", "send_goal", "/fibonacci", "example_interfaces/action/Fibonacci", "{order: 0}")
    assert refused.returncode == 0 and refused.stdout.endswith("Goal was rejected.\n")


@pytest.mark.parametrize(
    ("args", "error"),
    [
        (("/fibonacci", "actionlib_tutorials/action/Fibonacci", "{order: 3}"),
         "/fibonacci is an action of type example_interfaces/action/Fibonacci, not actionlib_tutorials/action/Fibonacci"),
        (("/fibonacci", "example_interfaces/action/Fibonacci", "{ordr: 3}"),
         "invalid example_interfaces/action/Fibonacci_Goal: ordr: Extra inputs are not permitted"),
        (("/fibonacci", "std_srvs/srv/Trigger"), "std_srvs/srv/Trigger is not an action type"),
        (("/fibonacci", "example_interfaces/action/Fibonaci"), "example_interfaces/action/Fibonaci"),
        (("/fibonacci", "example_interfaces/action/Fibonacci", "[1, 2]"), "DATA must be a mapping of fields"),
    ],
)  # fmt: skip
def test_cli_goal_errors_are_one_line(core: System, ros2_server: BackgroundProcess, args: tuple[str, ...], error: str) -> None:
    result = _skydeck(core, "action", "send_goal", *args)
    assert result.returncode == 1 and result.stdout == ""
    assert result.stderr.startswith("skydeck: error: ") and error in result.stderr and result.stderr.count("\n") == 1, result.stderr


def test_cli_ctrl_c_cancels_the_goal(core: System, ros2_server: BackgroundProcess) -> None:
    sender = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "action", "send_goal", "/fibonacci", "example_interfaces/action/Fibonacci",
         "{order: 40}", "--feedback"],
        name="skydeck action send_goal", cwd=REPO, env={**os.environ, "SKYDECK_CORE_URL": core.url, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    try:
        sender.wait_for_line("Feedback:", 30)
        sender.stop(signal.SIGINT)
    finally:
        sender.stop()
    assert sender.returncode == 130 and "Canceling goal..." in sender.lines and "Goal canceled." in sender.lines
    ros2_server.wait_for_line("Goal canceled", 10)
