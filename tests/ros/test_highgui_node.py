"""OpenCV windows on a real node and a real core: the topics and the input service appear under
the program's node (its namespace too), images go out only once someone reads them (through the
core's gateway, as the dashboard does) and reach a late reader at once (latched), input posted
to the gateway comes back from waitKey, and input that does not fit is answered, not raised.
``skydeck run`` adapts the real ``cv2`` (a program with no ROS node gets a node of its own)."""

from __future__ import annotations

import base64
import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

cv2 = pytest.importorskip("cv2", reason="the vision extra is not installed: make install-vision")

from services.ros.highgui.functions import HighGuiFunctions  # noqa: E402
from services.ros.highgui.host import connect  # noqa: E402
from services.ros.highgui.windows import HighGui  # noqa: E402
from tests.ros.conftest import until  # noqa: E402
from tests.sim_server.robot.room import call, latest  # noqa: E402
from tests.web_ui.system import REPO, System  # noqa: E402

pytestmark = [pytest.mark.timeout(90)]


def _graph(core: System) -> dict:
    graph = latest(core, "/api/graph")
    assert graph is not None
    return graph


def _topic_types(core: System, prefix: str) -> dict[str, str]:
    return {t["name"]: t["type"] for t in _graph(core)["topics"] if t["name"].startswith(prefix)}


def test_a_nodes_windows_go_through_the_core_only_while_read(rclpy, core: System) -> None:  # type: ignore[no-untyped-def]
    from websockets.sync.client import connect as ws_connect

    rclpy.create_node("tracker", namespace="/robot1")
    highgui = HighGuiFunctions(HighGui(connect))
    highgui.namedWindow("video window")
    highgui.createTrackbar("level", "video window", 10, 100, lambda pos: None)
    highgui.imshow("video window", np.full((24, 32, 3), (255, 0, 0), np.uint8))  # blue, in BGR
    until(lambda: "/robot1/tracker/opencv/video_window" in _topic_types(core, "/robot1/tracker/opencv"), what="the window's topic")
    assert _topic_types(core, "/robot1/tracker/opencv") == {
        "/robot1/tracker/opencv/windows": "skydeck_opencv/msg/Windows",
        "/robot1/tracker/opencv/video_window": "sensor_msgs/msg/CompressedImage",
    }
    services = {s["name"]: s["type"] for s in _graph(core)["services"]}
    assert services["/robot1/tracker/opencv/input"] == "skydeck_opencv/srv/WindowInput"
    described = latest(core, "/robot1/tracker/opencv/windows")
    assert described == {
        "windows": [
            {
                "name": "video window", "title": "video window", "topic": "/robot1/tracker/opencv/video_window",
                "width": 32, "height": 24, "display_width": 0, "display_height": 0, "mouse": False,
                "trackbars": [{"name": "level", "value": 10, "minimum": 0, "maximum": 100}],
            }
        ]
    }  # fmt: skip

    highgui.waitKey(1)
    assert latest(core, "/robot1/tracker/opencv/video_window") is None  # nobody reads it: not encoded
    stop = threading.Event()
    loop = threading.Thread(target=lambda: [highgui.waitKey(5) for _ in iter(stop.is_set, True)], daemon=True)
    loop.start()  # the program's loop: waitKey(5) again and again
    try:
        with ws_connect(f"{core.url.replace('http', 'ws')}/robot1/tracker/opencv/video_window") as reader:
            first = json.loads(reader.recv(timeout=20))
        image = cv2.imdecode(np.frombuffer(base64.b64decode(first["data"]), np.uint8), cv2.IMREAD_COLOR)
        assert first["format"] == "jpeg" and image.shape == (24, 32, 3)
        assert np.abs(image.astype(int) - (255, 0, 0)).max() < 10
        with ws_connect(f"{core.url.replace('http', 'ws')}/robot1/tracker/opencv/video_window") as late:
            assert json.loads(late.recv(timeout=10))["header"]["seq"] == first["header"]["seq"]  # latched, not encoded again
    finally:
        stop.set()
        loop.join(5)

    answer = call(core, "/robot1/tracker/opencv/input", {"window": "video window", "kind": "key", "key": ord("s")})
    assert answer == {"success": True, "message": "taken: the program sees it at its next cv2.waitKey"}
    assert highgui.waitKey(1000) == ord("s")
    refused = call(core, "/robot1/tracker/opencv/input", {"window": "video window", "kind": "trackbar", "trackbar": "level", "value": 101})
    assert refused == {"success": False, "message": "trackbar 'level' goes from 0 to 100, not to 101"}


def test_skydeck_run_serves_cv2s_windows_and_a_program_without_a_node_gets_one(core: System, tmp_path: Path) -> None:
    program = tmp_path / "show image.py"
    program.write_text(
        "import cv2\n"
        "import numpy as np\n"
        "from cv2 import imshow\n"
        "print('SERVED', type(cv2.imshow).__name__, imshow == cv2.imshow, type(cv2.GaussianBlur).__name__, flush=True)\n"
        "imshow('picture', np.zeros((8, 8), np.uint8))\n"
        "print('KEY', cv2.waitKey(0), flush=True)\n"
    )
    process = subprocess.Popen(
        [sys.executable, "-m", "services.cli", "run", str(program)],
        cwd=REPO, env={**os.environ, "SKYDECK_CORE_URL": core.url},
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        until(lambda: "/opencv_show_image/opencv/input" in {s["name"] for s in _graph(core)["services"]}, 30, "the program's node")
        assert call(core, "/opencv_show_image/opencv/input", {"window": "picture", "kind": "key", "key": 13})["success"]
        out, err = process.communicate(timeout=30)
    finally:
        process.kill()
    assert process.returncode == 0, err
    assert out.splitlines() == ["SERVED method True builtin_function_or_method", "KEY 13"]
