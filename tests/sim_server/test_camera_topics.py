"""The simulator's camera on two topics (raw rgb8 and JPEG) at the size and rate the user sets,
one render per tick for both, rendered only while read; its flags and parameters are checked."""

from __future__ import annotations

import asyncio
import io

import numpy as np
import ormsgpack
import pytest
from PIL import Image as PillowImage
from websockets.asyncio.client import connect

from services.runtime import NodeSettings, Parameter
from services.runtime.edge.links import stream_url
from services.runtime.ros_args import RosArguments, parse_ros_args, set_process_ros_arguments
from sim_server.camera_stream import COMPRESSED_TOPIC, RAW_TOPIC
from sim_server.drone.node import DroneSimNode
from sim_server.drone.settings import DroneSettings
from sim_server.node import main
from tests.conftest import wait_until

pytestmark = pytest.mark.timeout(90)


def _sim(**camera: float):
    return lambda settings: DroneSimNode(DroneSettings(seed=1, boxes=2, speed=None, **camera), settings)


async def _read(url: str, count: int) -> list[dict]:
    """``count`` msgpack frames of ``url``, unpacked."""
    async with connect(url, max_size=None) as websocket:
        return [ormsgpack.unpackb(await asyncio.wait_for(websocket.recv(), 30)) for _ in range(count)]


async def test_a_640x480_raw_image_reaches_a_msgpack_reader_of_the_core_bit_exact(core, start_node) -> None:
    sim = await start_node(_sim(camera_width=640, camera_height=480, camera_rate=10))
    via_core, direct = await asyncio.gather(
        _read(stream_url(core.url, RAW_TOPIC, encoding="msgpack"), 6),
        _read(stream_url(sim.url, RAW_TOPIC, encoding="msgpack"), 6),
    )
    first = via_core[0]
    assert (first["width"], first["height"], first["encoding"], first["step"]) == (640, 480, "rgb8", 1920)
    assert isinstance(first["data"], bytes) and len(first["data"]) == 640 * 480 * 3
    # The same frame (same seq) read from the node itself and through the core: the same bytes.
    by_seq = {frame["header"]["seq"]: frame for frame in direct}
    shared = [frame for frame in via_core if frame["header"]["seq"] in by_seq]
    assert shared, "no frame was read by both readers"
    for frame in shared:
        assert frame == by_seq[frame["header"]["seq"]]
    assert len(set(first["data"])) > 20  # a picture, not a blank frame


async def test_both_topics_come_from_one_render_per_tick(core, start_node) -> None:
    sim = await start_node(_sim(camera_width=160, camera_height=120, camera_rate=20))
    renders = 0
    render = sim.camera._render

    def counting(width: int, height: int) -> bytes:
        nonlocal renders
        renders += 1
        return render(width, height)

    sim.camera._render = counting
    async with (
        connect(stream_url(core.url, RAW_TOPIC, encoding="msgpack"), max_size=None) as raw,
        connect(stream_url(core.url, COMPRESSED_TOPIC, encoding="msgpack"), max_size=None) as jpeg,
    ):
        await wait_until(
            lambda: sim.camera.raw.get_subscription_count() and sim.camera.compressed.get_subscription_count(),
            what="both topics to be read",
        )
        raw_before, jpeg_before, renders_before = sim.camera.raw._endpoint.published_count, sim.camera.compressed._endpoint.published_count, renders
        pixels = ormsgpack.unpackb(await asyncio.wait_for(raw.recv(), 30))
        picture = ormsgpack.unpackb(await asyncio.wait_for(jpeg.recv(), 30))
        await wait_until(lambda: renders >= renders_before + 3, timeout_s=20, what="three more renders")
        published = (
            sim.camera.raw._endpoint.published_count - raw_before,
            sim.camera.compressed._endpoint.published_count - jpeg_before,
        )
    assert published == (renders - renders_before,) * 2
    decoded = np.asarray(PillowImage.open(io.BytesIO(picture["data"])).convert("RGB"), dtype=np.int16)
    assert decoded.shape == (120, 160, 3) and picture["format"] == "jpeg"
    raw_pixels = np.frombuffer(pixels["data"], dtype=np.uint8).reshape(120, 160, 3)
    assert raw_pixels.shape == decoded.shape  # the same camera; the JPEG is lossy, so not compared byte for byte


async def test_nothing_is_rendered_while_nobody_reads_and_the_rate_is_a_live_parameter(core, start_node) -> None:
    sim = await start_node(_sim(camera_rate=30))
    await asyncio.sleep(0.3)  # several camera periods pass with nobody watching
    assert sim.camera.raw._endpoint.published_count == sim.camera.compressed._endpoint.published_count == 0
    [result] = sim.set_parameters([Parameter("camera_rate", value=2.5)])
    assert result.successful and sim.camera.timer.timer_period_s == pytest.approx(0.4)
    [result] = sim.set_parameters([Parameter("camera_width", value=64)])
    assert result.successful
    frame = (await _read(stream_url(sim.url, RAW_TOPIC, encoding="msgpack"), 1))[0]
    assert (frame["width"], frame["height"], len(frame["data"])) == (64, 240, 64 * 240 * 3)
    [result] = sim.set_parameters([Parameter("camera_rate", value=60.0)])
    assert not result.successful and sim.camera.rate_hz == 2.5


@pytest.fixture
def ros_args():
    yield
    set_process_ros_arguments(RosArguments())


def test_the_camera_options_are_parameters_an_override_can_set(ros_args) -> None:
    set_process_ros_arguments(parse_ros_args(["-p", "camera_width:=640", "-p", "camera_rate:=12.5"]))
    sim = DroneSimNode(DroneSettings(seed=1, boxes=0), NodeSettings(port=0))
    sim.world.close()
    assert (sim.camera.width, sim.camera.height, sim.camera.rate_hz) == (640, 240, 12.5)
    assert sim.describe_parameter("camera_height").integer_range[0].to_value == 480


@pytest.mark.parametrize(
    ("flags", "expected"),
    [
        (["--camera-width", "641"], "--camera-width: Input should be less than or equal to 640"),
        (["--camera-height", "8"], "--camera-height: Input should be greater than or equal to 16"),
        (["--camera-rate", "31"], "--camera-rate: Input should be less than or equal to 30"),
        (["--camera-rate", "nan"], "--camera-rate: Input should be a finite number"),
        (["--camera-width", "wide"], "--camera-width: Input should be a valid integer"),
    ],
)
def test_bad_camera_flags_are_one_clear_line(capsys, flags: list[str], expected: str) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(flags)
    assert exit_info.value.code == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert f"error: {expected}" in error[-1]
    assert "Traceback" not in "\n".join(error)
