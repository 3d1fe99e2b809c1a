"""The ROS 2 bridge against unmodified rclpy programs over real DDS (Fast DDS), in processes of
their own: `skydeck launch robot --ros2` on one side, plain `python node.py` on the other."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from services.launch.background import BackgroundProcess
from tests.services.protocols.ros2.conftest import RosSystem

pytestmark = [pytest.mark.slow, pytest.mark.e2e, pytest.mark.timeout(180)]


def _line(process: BackgroundProcess, start: str, timeout_s: float) -> str:
    """The first line ``process`` prints that starts with ``start``."""
    return process.lines[process.wait_for_line(lambda line: line.startswith(start), timeout_s)]


@pytest.fixture(scope="module")
def robot(real_ros: None) -> Iterator[RosSystem]:
    """The robot world with the bridge (`skydeck launch robot --ros2`)."""
    system = RosSystem()
    system.launch("robot", "--seed", "3")
    yield system
    system.stop()


def test_an_unmodified_rclpy_talker_is_seen_by_topic_echo_and_listed_as_ros2(robot: RosSystem) -> None:
    talker = robot.rclpy("talker.py")
    try:
        echoed = robot.skydeck("topic", "echo", "/chatter", "-n", "2", "--timeout", "30", timeout_s=40)
        assert echoed.returncode == 0, echoed.stderr
        assert "data: hello " in echoed.stdout
        nodes = robot.skydeck("node", "list").stdout.splitlines()
        assert f"/talker (ROS 2, via /ros2_bridge_{robot.domain})" in nodes and f"/ros2_bridge_{robot.domain}" in nodes
        types = robot.skydeck("topic", "list", "-t").stdout.splitlines()
        assert "/chatter [std_msgs/msg/String] (from ROS 2)" in types
        assert "/scan [sensor_msgs/msg/LaserScan]" in types  # Skydeck's own, not marked
        info = robot.skydeck("node", "info", "/talker").stdout
        assert "/chatter [std_msgs/msg/String]" in info and f"System: ROS 2, via /ros2_bridge_{robot.domain}" in info
        doctor = robot.skydeck("doctor").stdout
        assert f"[ok] ROS 2 bridge /ros2_bridge_{robot.domain} joined DDS domain {robot.domain}" in doctor
    finally:
        talker.stop()


def test_an_rclpy_node_reads_scan_and_tf_static_drives_cmd_vel_and_runs_on_sim_time(robot: RosSystem) -> None:
    driver = robot.rclpy("robot_driver.py")
    scan = _line(driver, "scan ", 60).split()
    assert scan[1] == "360" and int(scan[2]) > 0 and scan[3] == "base_laser_link"  # 0.0: no return
    tf_static = _line(driver, "tf_static ", 10).split()
    assert "base_link>base_laser_link" in tf_static[1:]
    clock = float(_line(driver, "clock ", 10).split()[1])
    world_clock = robot.skydeck("topic", "echo", "/clock", "--once").stdout
    sim_seconds = int(world_clock.split("sec:")[1].split()[0])
    assert 0 < clock <= sim_seconds + 1  # the simulator's seconds since start, not the epoch's
    moved = float(_line(driver, "moved ", 30).split()[1])
    assert moved >= 0.3  # odometry changed: the robot drove on ROS 2's /cmd_vel


def test_services_both_ways(robot: RosSystem) -> None:
    lamp = robot.rclpy("lamp.py")
    try:
        _line(lamp, "serving", 30)
        robot.wait_for(lambda: "/lamp/set" in robot.skydeck("service", "list").stdout.split(), "/lamp/set in Skydeck")
        called = robot.skydeck("service", "call", "/lamp/set", "{data: true}", "--timeout", "20")
        assert called.returncode == 0, called.stderr
        assert "message: lamp on" in called.stdout
    finally:
        lamp.stop()
    caller = robot.rclpy("caller.py", "/simulator/reset")
    answer = _line(caller, "answer ", 60)
    assert answer.startswith("answer True world reset")


def test_a_type_skydeck_lacks_is_refused_in_one_line_and_the_rest_carries_on(robot: RosSystem) -> None:
    odd = robot.rclpy("odd_type.py")
    try:
        echoed = robot.skydeck("topic", "echo", "/fine", "-n", "1", "--timeout", "30", timeout_s=40)
        assert "data: fine" in echoed.stdout
        (launch,) = [p for p in robot.processes if p.name.startswith("skydeck launch")]
        refused = launch.lines[launch.wait_for_line("not bridging /odd", 10)]
        assert "lifecycle_msgs/msg/TransitionEvent has no Skydeck counterpart" in refused
        assert sum("not bridging /odd" in line for line in launch.lines) == 1
        assert "Traceback" not in "\n".join(launch.lines)
    finally:
        odd.stop()
