"""A ROS 2 workspace run the ROS 2 way against a real core: ``skydeck run PKG EXECUTABLE`` from
setup.py's entry points, a relative import, the workspace's own message package, and that
package's types known to the CLI, the core's API and a bag, as ROS's tools know a built one."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from services.bag import BagReader
from services.launch.background import BackgroundProcess
from tests.ros.workspace import write_workspace
from tests.web_ui.system import REPO, System

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(120)]


def skydeck(core: System, *args: str, cwd: Path = REPO, timeout_s: float = 30) -> subprocess.CompletedProcess[str]:
    """``skydeck ARGS`` run in ``cwd`` against ``core``."""
    return subprocess.run(
        [sys.executable, "-m", "services.cli", *args],
        cwd=cwd,
        env={**os.environ, "SKYDECK_CORE_URL": core.url},
        capture_output=True,
        text=True,
        timeout=timeout_s,
        check=False,
    )


def run_node(core: System, *args: str, cwd: Path) -> BackgroundProcess:
    return BackgroundProcess(
        [sys.executable, "-m", "services.cli", "run", *args],
        name=f"skydeck run {' '.join(args)}",
        cwd=cwd,
        env={**os.environ, "SKYDECK_CORE_URL": core.url, "PYTHONUNBUFFERED": "1"},
    )


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_workspace(tmp_path_factory.mktemp("ros2_ws"))


@pytest.fixture(scope="module")
def talker(core: System, workspace: Path) -> Iterator[BackgroundProcess]:
    """``ros2 run py_pubsub talker``, as `skydeck run` from the workspace folder."""
    process = run_node(core, "py_pubsub", "talker", cwd=workspace)
    try:
        process.wait_for_line('Publishing: "3"', 60)
        yield process
    finally:
        process.stop(signal.SIGINT, timeout_s=10)


def test_topic_echo_prints_the_workspace_message(core: System, talker: BackgroundProcess) -> None:
    echoed = skydeck(core, "topic", "echo", "/topic", "--once")
    assert echoed.returncode == 0, echoed.stderr
    number = int(echoed.stdout.split("num:")[1].split()[0])
    assert number >= 3
    sphere = skydeck(core, "topic", "echo", "/sphere", "--once", "--json")
    assert sphere.stdout.strip() == '{"center":{"x":1.0,"y":2.0,"z":3.0},"radius":0.5}'


def test_interface_show_knows_it_from_the_core_anywhere(core: System, talker: BackgroundProcess, tmp_path: Path) -> None:
    shown = skydeck(core, "interface", "show", "tutorial_interfaces/msg/Sphere", cwd=tmp_path)  # no workspace here
    assert shown.returncode == 0, shown.stderr
    assert shown.stdout == "geometry_msgs/Point center\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\nfloat64 radius\n"
    graph = skydeck(core, "topic", "list", "-t")
    assert "/topic [tutorial_interfaces/msg/Num]" in graph.stdout


def test_interface_show_and_list_read_the_workspace_itself(core: System, workspace: Path) -> None:
    shown = skydeck(core, "interface", "show", "tutorial_interfaces/srv/AddThreeInts", cwd=workspace)
    assert shown.stdout == "int64 a\nint64 b\nint64 c\n---\nint64 sum\n", shown.stderr
    listed = skydeck(core, "interface", "list", "-s", cwd=workspace).stdout.split()
    assert "tutorial_interfaces/srv/AddThreeInts" in listed and "example_interfaces/srv/AddTwoInts" in listed
    actions = skydeck(core, "interface", "list", "-a", cwd=workspace).stdout.split()
    assert "example_interfaces/action/Fibonacci" in actions and all("/action/" in name for name in actions)


def test_the_core_learned_the_type_from_the_node(core: System, talker: BackgroundProcess) -> None:
    reply = httpx.get(f"{core.url}/api/interfaces/tutorial_interfaces/msg/Sphere", timeout=5).json()
    assert reply["definitions"] == {"tutorial_interfaces/msg/Sphere": "geometry_msgs/Point center\nfloat64 radius\n"}
    assert reply["default"] == {"center": {"x": 0.0, "y": 0.0, "z": 0.0}, "radius": 0.0}
    names = [i["name"] for i in httpx.get(f"{core.url}/api/interfaces", timeout=5).json()["interfaces"]]
    assert "tutorial_interfaces/msg/Num" in names


def test_a_bag_records_the_workspace_message(core: System, talker: BackgroundProcess, tmp_path: Path) -> None:
    bag = tmp_path / "nums.mcap"
    recorded = skydeck(core, "bag", "record", "/topic", "-o", str(bag), "--max-duration", "2", timeout_s=40)
    assert recorded.returncode == 0, recorded.stderr
    with BagReader(bag) as reader:
        topic = reader.summary.topic("/topic")
        assert topic is not None and topic.type_name == "tutorial_interfaces/msg/Num" and topic.count >= 5
    info = skydeck(core, "bag", "info", str(bag)).stdout
    assert "Topic: /topic | Type: tutorial_interfaces/msg/Num" in info
    echo = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "topic", "echo", "/replayed", "--once", "--timeout", "30"],
        name="echo /replayed",
        env={**os.environ, "SKYDECK_CORE_URL": core.url, "PYTHONUNBUFFERED": "1"},
    )
    try:
        played = skydeck(core, "bag", "play", str(bag), "--remap", "/topic:=/replayed", "--wait-for-subscribers", cwd=tmp_path)
        assert played.returncode == 0, played.stderr
        echo.wait_for_line("num: ", 30)
    finally:
        echo.stop()


def test_listener_as_a_file_in_its_package_and_a_custom_service(core: System, workspace: Path, talker: BackgroundProcess) -> None:
    listener = run_node(core, "src/py_pubsub/py_pubsub/subscriber_member_function.py", cwd=workspace)
    service = run_node(core, "py_pubsub", "service", cwd=workspace)
    try:
        listener.wait_for_line("I heard:", 60)
        client = run_node(core, "py_pubsub", "client", "2", "3", "4", cwd=workspace)
        try:
            client.wait_for_line("Result of add_three_ints: for 2 + 3 + 4 = 9", 60)
        finally:
            client.stop(signal.SIGINT, timeout_s=10)
        called = skydeck(core, "service", "call", "/add_three_ints", "{a: 1, b: 2, c: 3}")
        assert called.returncode == 0 and "sum: 6" in called.stdout, called.stdout + called.stderr
    finally:
        listener.stop(signal.SIGINT, timeout_s=10)
        service.stop(signal.SIGINT, timeout_s=10)


def test_unknown_package_and_executable_are_one_line(core: System, workspace: Path) -> None:
    missing = skydeck(core, "run", "py_pubsb", "talker", cwd=workspace)
    assert missing.returncode == 1
    assert missing.stderr.startswith("skydeck: error: no package py_pubsb in ")
    assert "(found: py_pubsub, tutorial_interfaces)" in missing.stderr and missing.stderr.count("\n") == 1
    wrong = skydeck(core, "run", "py_pubsub", "takler", "--workspace", str(workspace))  # from elsewhere
    assert wrong.stderr == (
        "skydeck: error: package py_pubsub has no executable 'takler'; its entry points: client, listener, service, talker\n"
    )


def test_a_malformed_message_file_is_one_line_naming_file_and_line(core: System, workspace: Path, tmp_path: Path) -> None:
    broken = tmp_path / "ws"
    write_workspace(broken)
    (broken / "src/tutorial_interfaces/msg/Num.msg").write_text("# a count\nflaot64 num\n")
    ran = skydeck(core, "run", "py_pubsub", "talker", cwd=broken)
    assert ran.returncode == 1
    assert ran.stderr.startswith(
        "skydeck: error: tutorial_interfaces/msg/Num.msg:2: unknown type 'flaot64' (did you mean float64? "
    )
    assert ran.stderr.count("\n") == 1 and "Traceback" not in ran.stderr
