"""tf2 against the robot world, as a course's later weeks use it: a ROS 2 file (tf2_ros with its
node, tf2_geometry_msgs, tf_transformations) and a ROS 1 file (tf and tf2_ros after
rospy.init_node), run unchanged by ``skydeck run`` while the robot drives. What they read from
``/tf`` is checked against ``/odom`` as this test records it itself, stamp by stamp."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

from tests.ros.conftest import CORPUS, no_skydeck_frames, ros_file
from tests.sim_server.robot.room import Recorder, reset_room, start_room, yaw_of
from tests.web_ui.system import System

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(180)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "1", "--speed", "2")
    yield system
    system.stop()


@pytest.fixture
def fresh(room: System) -> System:
    return reset_room(room)


def _stamp_key(message: dict) -> str:
    stamp = message["header"]["stamp"]
    return f"{stamp['sec']}.{stamp['nanosec']:09d}"


def _odom_by_stamp(recorder: Recorder) -> dict[str, tuple[float, float, float]]:
    poses = {}
    for m in recorder.messages:
        p = m["pose"]["pose"]
        poses[_stamp_key(m)] = (p["position"]["x"], p["position"]["y"], yaw_of(p["orientation"]))
    return poses


def _rows(lines: list[str], label: str) -> list[list[str]]:
    return [line.split()[1:] for line in lines if line.startswith(label + " ")]


def _same_pose(tf_pose: tuple[float, float, float], odom: tuple[float, float, float]) -> bool:
    return math.dist(tf_pose[:2], odom[:2]) < 1e-9 and abs(math.remainder(tf_pose[2] - odom[2], math.tau)) < 1e-9


def test_a_ros2_tf2_listener_reads_odom_to_base_link_as_odom_says(fresh: System) -> None:
    with Recorder(fresh, "/odom") as odom, ros_file(fresh, CORPUS / "ros2" / "tf_odom_listener.py", sim_time=False) as node:
        node.wait_for_line(lambda line: len(_rows(node.lines, "AT")) >= 20 and len(_rows(node.lines, "LATEST")) >= 10, 90)
        node.wait_for_line("CAN ", 30)
        lines = list(node.lines)  # before the Ctrl-C, which may cut a print short
    poses = _odom_by_stamp(odom)
    checked = 0
    for label in ("AT", "LATEST"):
        for stamp, x, y, yaw in _rows(lines, label):
            if stamp in poses:  # the recorder may have joined after the file's first messages
                assert _same_pose((float(x), float(y), float(yaw)), poses[stamp]), (label, stamp, x, y, yaw, poses[stamp])
                checked += 1
    assert checked >= 25, node.tail()
    moved = [tuple(map(float, row[1:3])) for row in _rows(lines, "LATEST")]
    assert math.dist(moved[0], moved[-1]) > 0.05  # it drove: the transform followed the robot
    # The camera (a static link the file broadcast) chained onto the dynamic odom -> base_link.
    for stamp, px, py, pz, ax, ay in _rows(lines, "CAMERA"):
        if stamp not in poses:
            continue
        x, y, yaw = poses[stamp]
        # 1 m ahead of a camera 0.2 m forward, 0.1 m up, looking left: (0.2, 1.0, 0.1) on the robot
        expected = (x + 0.2 * math.cos(yaw) - 1.0 * math.sin(yaw), y + 0.2 * math.sin(yaw) + 1.0 * math.cos(yaw), 0.1)
        assert math.dist((float(px), float(py), float(pz)), expected) < 1e-9
        assert math.dist((float(ax), float(ay)), expected[:2]) < 1e-9  # buffer.transform() agrees
        checked += 1
    text = "\n".join(lines)
    assert "FUTURE Lookup would require extrapolation into the future.  Requested time " in text
    assert ", when looking up transform from frame [base_link] to frame [odom]" in text
    assert "PAST Lookup would require extrapolation into the past.  Requested time 0.000000 but the earliest data is at time " in text
    assert 'LOOKUP "base_footprint" passed to lookupTransform argument source_frame does not exist.' in text
    assert "CAN True" in text
    assert no_skydeck_frames(node.lines) and not any("Traceback" in line for line in node.lines), node.tail()


def test_a_ros1_tf_listener_and_broadcaster_follow_the_robot(fresh: System) -> None:
    with Recorder(fresh, "/odom") as odom, ros_file(fresh, CORPUS / "ros1" / "tf_odom_listener.py", sim_time=False) as node:
        node.wait_for_line(lambda line: len(_rows(node.lines, "CARROT")) >= 10, 90)
        lines = list(node.lines)  # before the Ctrl-C, which may cut a print short
    poses = _odom_by_stamp(odom)
    text = "\n".join(lines)
    assert "READY" in text
    assert 'WAITED Invalid frame ID "nowhere" passed to canTransform argument source_frame - frame does not exist' in text
    checked = 0
    for stamp, x, y, yaw in _rows(lines, "LATEST"):
        if stamp in poses:
            assert _same_pose((float(x), float(y), float(yaw)), poses[stamp]), (stamp, x, y, yaw, poses[stamp])
            checked += 1
    for stamp, cx, cy in _rows(lines, "CARROT"):
        if stamp in poses:
            x, y, yaw = poses[stamp]
            assert math.dist((float(cx), float(cy)), (x + 0.5 * math.cos(yaw), y + 0.5 * math.sin(yaw))) < 1e-9
            checked += 1
    assert checked >= 10, node.tail()
    turned = [float(row[3]) for row in _rows(lines, "LATEST")]
    assert turned[-1] < turned[0] - 0.05  # it turned right (angular.z < 0), as tf saw it
    assert no_skydeck_frames(node.lines) and not any("Traceback" in line for line in node.lines), node.tail()
