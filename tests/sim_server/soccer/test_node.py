"""The soccer room as a node, over real sockets: the core and `skydeck run sim --world soccer`
in subprocesses. Each robot's camera is at ``camera/image_raw`` (rgb8, under its namespace)
with ``camera/camera_info``, rendered only once someone reads it, at the ``--camera-rate`` the
flag sets; its frame hangs off base_link on /tf_static; the ball's truth is /simulator/balls;
the launch file ``soccer`` starts it."""

from __future__ import annotations

import base64
import math
from collections.abc import Iterator

import pytest

from services.launch.plan import LaunchOptions, plan_launch
from services.launch.spec import find_launch_file, load_launch_file
from sim_server.soccer.limits import BALL_START_M
from tests.conftest import free_port_block
from tests.sim_server.robot.room import Recorder, call, latest, wait_for
from tests.web_ui.system import System

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(120)]


def _soccer(*sim_args: str) -> System:
    system = System(free_port_block(2))
    try:
        system.start("core", ["core"], system.base_port)
        system.start("sim", ["run", "sim", "--world", "soccer", *sim_args], system.base_port + 1)
        wait_for(system, "/simulator/balls", lambda m: True)
    except BaseException:
        system.stop()
        raise
    return system


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = _soccer("--seed", "1", "--camera-rate", "8", "--camera-width", "160", "--camera-height", "120")
    yield system
    system.stop()


def _types(system: System) -> dict[str, str]:
    graph = latest(system, "/api/graph")
    assert graph is not None
    return {t["name"]: t["type"] for t in graph["topics"]}


def test_the_robots_camera_renders_only_while_read(room: System) -> None:
    types = _types(room)
    assert types["/camera/image_raw"] == "sensor_msgs/msg/Image"
    assert types["/camera/camera_info"] == "sensor_msgs/msg/CameraInfo"
    assert types["/simulator/balls"] == "geometry_msgs/msg/PoseArray"
    assert latest(room, "/camera/image_raw") is None  # nobody has read it: never rendered
    assert latest(room, "/simulator/world")["world"] == "soccer"
    soccer = latest(room, "/api/config")["worlds"]["soccer"]
    assert soccer["extends"] == "robot"  # the robot world's clients (the dashboard) show it as that world
    assert soccer["topics"]["camera_image"] == "camera/image_raw" and soccer["topics"]["balls"] == "/simulator/balls"
    assert soccer["room_half_size_m"] == 4.0 and soccer["ball_radius_m"] == pytest.approx(0.095)
    with Recorder(room, "/camera/image_raw") as images, Recorder(room, "/camera/camera_info") as infos:
        wait_for(room, "/camera/image_raw", lambda m: len(images.messages) >= 3, timeout_s=30)
    image = images.messages[-1]
    assert (image["encoding"], image["width"], image["height"], image["step"]) == ("rgb8", 160, 120, 480)
    assert image["header"]["frame_id"] == "camera" and len(base64.b64decode(image["data"])) == 160 * 120 * 3
    info = infos.messages[-1]
    focal = 60.0 / math.tan(math.radians(30.0))  # half the height over tan(half the vertical field of view)
    assert info["k"] == pytest.approx([focal, 0, 80, 0, focal, 60, 0, 0, 1])
    assert (info["width"], info["height"], info["distortion_model"]) == (160, 120, "plumb_bob")
    stamps = {(m["header"]["stamp"]["sec"], m["header"]["stamp"]["nanosec"]) for m in infos.messages}
    assert any((m["header"]["stamp"]["sec"], m["header"]["stamp"]["nanosec"]) in stamps for m in images.messages)
    params = call(room, "/sim/get_parameters", {"names": ["camera_rate"]})
    assert params["values"][0]["double_value"] == 8.0  # --camera-rate


def test_the_camera_frame_is_on_tf_static_and_the_ball_on_its_topic(room: System) -> None:
    static = latest(room, "/tf_static")
    links = {(t["header"]["frame_id"], t["child_frame_id"]): t["transform"] for t in static["transforms"]}
    camera = links[("base_link", "camera")]
    assert camera["translation"] == pytest.approx({"x": 0.12, "y": 0.0, "z": 0.16})
    assert ("base_link", "base_laser_link") in links and ("map", "odom") in links
    ball = latest(room, "/simulator/balls")
    assert ball["header"]["frame_id"] == "map"
    position = ball["poses"][0]["position"]
    assert (position["x"], position["y"]) == pytest.approx(BALL_START_M, abs=1e-3)
    answer = call(room, "/simulator/reset")
    assert answer["success"] is True and "the ball on its spot" in answer["message"]


def test_with_several_robots_each_has_its_camera_in_its_namespace() -> None:
    system = _soccer("--robots", "2", "--seed", "2", "--camera-width", "64", "--camera-height", "48")
    try:
        types = _types(system)
        assert {"/robot1/camera/image_raw", "/robot2/camera/image_raw", "/robot2/camera/camera_info"} <= set(types)
        with Recorder(system, "/robot2/camera/image_raw") as images:
            wait_for(system, "/robot2/camera/image_raw", lambda m: len(images.messages) >= 1, timeout_s=30)
        assert images.messages[0]["header"]["frame_id"] == "robot2/camera"
        assert latest(system, "/robot1/camera/image_raw") is None  # robot 1's is not read: not rendered
        links = {(t["header"]["frame_id"], t["child_frame_id"]) for t in latest(system, "/tf_static")["transforms"]}
        assert {("robot1/base_link", "robot1/camera"), ("robot2/base_link", "robot2/camera")} <= links
    finally:
        system.stop()


def test_the_soccer_launch_file_starts_the_core_and_the_soccer_room() -> None:
    path = find_launch_file("soccer")
    options = LaunchOptions(seed=3, speed="max", world_options={"robots": 2, "obstacles": 0})
    plans = plan_launch(load_launch_file(path, {"camera_rate": "12"}), options)
    assert [plan.name for plan in plans] == ["core", "sim"]
    assert plans[1].args == (
        "--world", "soccer", "--speed", "max", "--seed", "3", "--robots", "2", "--obstacles", "0", "--camera-rate", "12",
    )  # fmt: skip
    default = plan_launch(load_launch_file(path, {}), LaunchOptions(seed=3))[1]
    assert default.args[-2:] == ("--camera-rate", "5")
