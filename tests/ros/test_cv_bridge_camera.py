"""cv_bridge on real Skydeck topics: a ROS 2 file run by ``skydeck run`` reads the robot world's
camera (``/simulator/camera/image_raw``, rgb8, and ``/simulator/camera``, JPEG) through CvBridge,
and republishes a grey image and a PNG of its edges. What it printed and published is checked
against the camera frames this test records itself, frame by frame."""

from __future__ import annotations

import base64
from collections.abc import Iterator

import numpy as np
import pytest

cv2 = pytest.importorskip("cv2", reason="the vision extra is not installed: make install-vision")

from tests.ros.conftest import CORPUS, no_skydeck_frames, ros_file  # noqa: E402
from tests.sim_server.robot.room import Recorder, start_room  # noqa: E402
from tests.web_ui.system import System  # noqa: E402

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(180)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "2")
    yield system
    system.stop()


def _key(message: dict) -> str:
    stamp = message["header"]["stamp"]
    return f"{stamp['sec']}.{stamp['nanosec']:09d}"


def _pixels(message: dict, channels: int) -> np.ndarray:
    data = np.frombuffer(base64.b64decode(message["data"]), dtype=np.uint8)
    shape = (message["height"], message["width"], channels) if channels > 1 else (message["height"], message["width"])
    return data.reshape(shape)


def test_a_camera_node_converts_the_simulators_frames_with_cv_bridge(room: System) -> None:
    with (
        Recorder(room, "/simulator/camera/image_raw") as raw,
        Recorder(room, "/camera/gray") as gray,
        Recorder(room, "/camera/edges/compressed") as edges,
        ros_file(room, CORPUS / "ros2" / "camera_bridge.py", sim_time=False) as node,
    ):
        node.wait_for_line(lambda line: sum(x.startswith("RAW ") for x in node.lines) >= 5, 90)
        node.wait_for_line("JPEG ", 30)
        lines = list(node.lines)  # before the Ctrl-C, which may cut a print short
    frames = {_key(m): _pixels(m, 3) for m in raw.messages if m["encoding"] == "rgb8"}
    checked = 0
    for line in lines:
        if not line.startswith("RAW "):
            continue
        stamp, width, height, blue, green, red = line.split()[1:]
        rgb = frames.get(stamp)
        if rgb is None:
            continue
        assert (int(width), int(height)) == (rgb.shape[1], rgb.shape[0])
        wanted = [rgb[:, :, 2].mean(), rgb[:, :, 1].mean(), rgb[:, :, 0].mean()]  # bgr8: the channels turned round
        assert np.allclose([float(blue), float(green), float(red)], wanted, rtol=0, atol=1e-9), (line, wanted)
        checked += 1
    assert checked >= 3, node.tail()
    for message in gray.messages:
        assert message["encoding"] == "mono8" and message["step"] == message["width"]
        rgb = frames.get(_key(message))  # the grey image keeps its frame's header
        if rgb is not None:
            assert np.array_equal(_pixels(message, 1), cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY))
            checked += 1
    assert checked >= 6
    png = next(m for m in edges.messages)
    assert png["format"] == "png"
    decoded = cv2.imdecode(np.frombuffer(base64.b64decode(png["data"]), np.uint8), cv2.IMREAD_UNCHANGED)
    assert decoded.ndim == 2 and set(np.unique(decoded)) <= {0, 255}
    jpeg_means = [list(map(float, line.split()[2:])) for line in lines if line.startswith("JPEG ")]
    raw_means = [[f[:, :, 2].mean(), f[:, :, 1].mean(), f[:, :, 0].mean()] for f in frames.values()]
    assert min(np.abs(np.subtract(jpeg_means[-1], means)).max() for means in raw_means) < 4  # the same view, lossy
    assert no_skydeck_frames(node.lines) and not any("Traceback" in line for line in node.lines), node.tail()
