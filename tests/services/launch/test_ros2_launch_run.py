"""ROS 2 launch files run for real: ``skydeck launch launch_demo pair.launch.{py,xml,yaml}`` from
the workspace folder starts the core and the package's talker and listener, and the core shows
the launch file's namespace, remap and parameters (params file and argument) on the nodes."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from services.launch.background import BackgroundProcess
from services.runtime.ports import free_port_block
from tests.services.launch.ros2_workspace import write_launch_workspace

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_launch_workspace(tmp_path_factory.mktemp("ros2_launch_ws"))


@pytest.fixture(scope="module", params=["pair.launch.py", "pair.launch.xml", "pair.launch.yaml"])
def launched(request: pytest.FixtureRequest, workspace: Path) -> Iterator[tuple[str, BackgroundProcess]]:
    """The launch running, once the listener has heard the talker; its core's URL."""
    base = free_port_block(4)
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "launch", "launch_demo", request.param, "greeting:=hey",
         "--base-port", str(base), "--rosbridge-port", "0", "--foxglove-port", "0"],
        name=f"skydeck launch launch_demo {request.param}",
        cwd=workspace,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    try:
        process.wait_for_line("[robot1/ear] [INFO] [robot1.ear]: heard hey", 60)
        yield f"http://127.0.0.1:{base}", process
    finally:
        assert process.stop(signal.SIGINT, timeout_s=20)
    assert not any("Traceback" in line for line in process.lines), process.tail(20)


def _skydeck(core_url: str, *args: str) -> str:
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", *args],
        env={**os.environ, "SKYDECK_CORE_URL": core_url},
        capture_output=True, text=True, timeout=30, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_nodes_come_up_in_their_namespace_with_the_remap(launched: tuple[str, BackgroundProcess]) -> None:
    url, _process = launched
    nodes = _skydeck(url, "node", "list").split()
    assert {"/robot1/speaker", "/robot1/ear"} <= set(nodes)
    topics = _skydeck(url, "topic", "list").split()
    assert "/robot1/news" in topics and "/robot1/chatter" not in topics
    info = _skydeck(url, "node", "info", "/robot1/ear")
    assert "/robot1/news" in info


def test_the_parameters_come_from_the_file_and_the_argument(launched: tuple[str, BackgroundProcess]) -> None:
    url, _process = launched
    assert _skydeck(url, "param", "get", "/robot1/speaker", "robot_id").strip() == "Integer value is: 7"
    assert _skydeck(url, "param", "get", "/robot1/speaker", "rate").strip() == "Double value is: 20.0"
    assert _skydeck(url, "param", "get", "/robot1/speaker", "greeting").strip() == "String value is: hey"


def test_the_launch_prints_its_nodes_by_graph_name(launched: tuple[str, BackgroundProcess]) -> None:
    _url, process = launched
    starting = next(line for line in process.lines if line.startswith("[launch] starting"))
    assert "robot1/speaker" in starting and "robot1/ear" in starting


def test_an_error_in_a_launch_file_is_one_line_and_starts_nothing(workspace: Path) -> None:
    bad = workspace / "src" / "launch_demo" / "launch" / "bad.launch.py"
    bad.write_text("from launch import LaunchDescription\nfrom launch.actions import ExecuteProcess\n")
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "launch", "launch_demo", "bad.launch.py"],
        cwd=workspace, capture_output=True, text=True, timeout=30, check=False,
    )  # fmt: skip
    assert done.returncode == 1
    assert done.stderr == f"skydeck: error: {bad}:2: launch.actions.ExecuteProcess is not provided by Skydeck (Skydeck's has: DeclareLaunchArgument, GroupAction, IncludeLaunchDescription, SetLaunchConfiguration)\n"
