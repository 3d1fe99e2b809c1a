"""Two Skydeck systems, each with its bridge, on one DDS domain: a message crosses once, and
never comes back; and the bridge without its extra is one line."""

from __future__ import annotations

import json
import sys
from collections import Counter

import pytest

from services.launch.background import BackgroundProcess
from tests.services.protocols.ros2.conftest import NODES, RosSystem

pytestmark = [pytest.mark.slow, pytest.mark.e2e, pytest.mark.timeout(180)]


def _echo(system: RosSystem, topic: str) -> BackgroundProcess:
    return system.start([sys.executable, "-m", "services.cli", "topic", "echo", topic, "--json"], name=f"echo {topic}")


def _numbers(process: BackgroundProcess, prefix: str = "") -> list[int]:
    values = []
    for line in list(process.lines):
        if prefix and line.startswith(prefix):
            values.append(int(line.split()[1]))
        elif not prefix and line.startswith("{"):
            values.append(json.loads(line)["data"])
    return values


def test_two_bridges_in_one_domain_deliver_each_message_once(real_ros: None) -> None:
    one, two = RosSystem(), RosSystem()
    try:
        one.launch("robot", "--exclude", "sim")
        two.launch("robot", "--exclude", "sim")
        counter = one.rclpy("counter.py")
        counter.wait_for_line("listening", timeout_s=30)
        here, there = _echo(one, "/count"), _echo(two, "/count")
        publisher = one.start(
            [sys.executable, "-m", "services.cli", "run", str(NODES / "count_publisher.py")], name="skydeck run count_publisher"
        )
        # Inside `skydeck run`, rclpy is Skydeck's façade even with the real one installed.
        façade = publisher.lines[publisher.wait_for_line("rclpy is", timeout_s=30)]
        assert "/services/ros/rclpy/" in façade
        one.wait_for(lambda: len(_numbers(counter, "got ")) >= 40 and len(_numbers(there)) >= 40, "40 messages across", 60)
        publisher.stop()
        for name, values in (("ROS 2", _numbers(counter, "got ")), ("the other system", _numbers(there)), ("its own", _numbers(here))):
            assert len(values) >= 20, f"{name} got {len(values)} messages"
            twice = [value for value, count in Counter(values).items() if count > 1]
            assert not twice, f"{name} got {twice} more than once"
            assert values == sorted(values), f"{name} got them out of order"
    finally:
        one.stop()
        two.stop()


def test_without_the_extra_the_bridge_is_one_line(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    from importlib.metadata import PackageNotFoundError

    from services.cli.main import main
    from services.protocols.ros2 import extra

    def not_installed(name: str) -> str:
        raise PackageNotFoundError(name)

    monkeypatch.setattr(extra, "version", not_installed)
    assert main(["bridge", "ros2"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [
        "skydeck: error: the ROS 2 bridge needs ROS 2's Python packages (ros-rclpy, ros-rmw-fastrtps-cpp, "
        "ros-std-msgs not installed): run `make install-ros2` (or `pip install -e '.[ros2]'`, then "
        "`python -m services.protocols.ros2.interface_build`)"
    ]
    assert main(["launch", "robot", "--ros2"]) == 1
    assert capsys.readouterr().err.count("\n") == 1


def test_bad_options_are_one_line(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    from services.cli.main import main

    assert main(["bridge", "ros2", "--domain", "233"]) == 1
    assert main(["bridge", "ros2", "--topics", "(unclosed"]) == 1
    assert main(["bridge", "ros2", "--services", "*"]) == 1
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines[0] == "skydeck: error: --domain must be 0 to 232, not 233"
    assert lines[1].startswith("skydeck: error: --topics '(unclosed' is not a regular expression: ")
    assert lines[2].startswith("skydeck: error: --services '*' is not a regular expression: ")
    monkeypatch.setenv("ROS_DOMAIN_ID", "lab")
    assert main(["bridge", "ros2"]) == 1
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("skydeck: error: ROS_DOMAIN_ID: ") and line.endswith("(a DDS domain id, 0 to 232)")
