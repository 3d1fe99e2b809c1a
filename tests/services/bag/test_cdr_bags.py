"""Recordings in ROS 2's encoding (``bag record --encoding cdr``): read by independent readers
(``mcap-ros2-support``, ``rosbags``), and recordings written by an independent writer read and
played by Skydeck."""

from __future__ import annotations

import asyncio
import json
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from mcap_ros2.writer import Writer as Ros2Writer

from services.bag import BagReader, BagWriter, PlayOptions
from shared_models.builtin_interfaces import Time
from shared_models.sensor_msgs import LaserScan, Range
from shared_models.std_msgs import Header, String
from shared_models.tf2_msgs import TFMessage
from tests.services.bag.test_record_play import START_NS, Listener, frames, play

pytestmark = pytest.mark.timeout(60)

SCAN = LaserScan(
    header=Header(seq=4, stamp=Time(sec=12, nanosec=5), frame_id="base_laser_link"),
    angle_increment=0.015625, range_min=0.25, range_max=5.0, ranges=[0.0, 1.5, 4.75],
)
TF = TFMessage.model_validate({"transforms": [{"header": {"frame_id": "odom"}, "child_frame_id": "base_link",
                                               "transform": {"translation": {"x": 1.0}, "rotation": {"w": 1.0}}}]})


def _cdr_bag(path: Path) -> Path:
    writer = BagWriter.create(path, metadata={}, encoding="cdr")
    scan = writer.add_topic("/scan", "sensor_msgs/msg/LaserScan")
    clock = writer.add_topic("/clock", "builtin_interfaces/msg/Time")
    tf = writer.add_topic("/tf", "tf2_msgs/msg/TFMessage")
    for i in range(3):
        writer.write(clock, Time(sec=12, nanosec=i).model_dump_json(), START_NS + i)
    writer.write(scan, SCAN.model_dump_json(), START_NS + 10)
    writer.write(tf, TF.model_dump_json(), START_NS + 20)
    writer.close()
    return path


def test_a_cdr_recording_is_ros2s_profile_schemas_and_messages(tmp_path: Path) -> None:
    path = _cdr_bag(tmp_path / "run.mcap")
    with path.open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
        assert {s.name: s.encoding for s in summary.schemas.values()} == {
            "sensor_msgs/msg/LaserScan": "ros2msg", "rosgraph_msgs/msg/Clock": "ros2msg", "tf2_msgs/msg/TFMessage": "ros2msg",
        }
        assert {c.message_encoding for c in summary.channels.values()} == {"cdr"}
        decoded = {channel.topic: message for _, channel, _, message in reader.iter_decoded_messages()}
    scan = decoded["/scan"]
    assert list(scan.ranges) == pytest.approx([0.0, 1.5, 4.75]) and scan.header.frame_id == "base_laser_link"
    assert (scan.header.stamp.sec, scan.header.stamp.nanosec) == (12, 5)
    assert (decoded["/clock"].clock.sec, decoded["/clock"].clock.nanosec) == (12, 2)
    assert decoded["/tf"].transforms[0].child_frame_id == "base_link"


def test_rosbags_reads_the_schemas_and_the_messages(tmp_path: Path) -> None:
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    path = _cdr_bag(tmp_path / "run.mcap")
    store = get_typestore(Stores.EMPTY)
    with path.open("rb") as stream:
        reader = make_reader(stream)
        for schema in reader.get_summary().schemas.values():
            store.register(_types(schema.name, schema.data.decode(), get_types_from_msg))
        messages = {channel.topic: (schema.name, message.data) for schema, channel, message in reader.iter_messages()}
    name, data = messages["/scan"]
    scan = store.deserialize_cdr(data, name)
    assert scan.header.frame_id == "base_laser_link" and list(scan.ranges) == pytest.approx([0.0, 1.5, 4.75])
    name, data = messages["/tf"]
    assert store.deserialize_cdr(data, name).transforms[0].transform.translation.x == 1.0


def _types(name: str, text: str, parse):  # type: ignore[no-untyped-def]
    """rosbags' types of a ros2msg schema: the main definition and each `MSG:` section."""
    types = {}
    sections = text.split("=" * 80 + "\n")
    types.update(parse(sections[0], name))
    for section in sections[1:]:
        header, _, body = section.partition("\n")
        package, short = header.removeprefix("MSG: ").split("/")
        types.update(parse(body, f"{package}/msg/{short}"))
    return types


def test_skydeck_reads_back_its_own_cdr_recording_as_frames(tmp_path: Path) -> None:
    with BagReader(_cdr_bag(tmp_path / "run.mcap")) as bag:
        assert {t.topic: (t.type_name, t.encoding) for t in bag.summary.topics} == {
            "/scan": ("sensor_msgs/msg/LaserScan", "cdr"),
            "/clock": ("builtin_interfaces/msg/Time", "cdr"),  # Skydeck's /clock type again
            "/tf": ("tf2_msgs/msg/TFMessage", "cdr"),
        }
        read = {m.topic: m.frame for m in bag.messages()}
    scan = SCAN.model_copy(update={"header": SCAN.header.model_copy(update={"seq": 0})})  # seq is ROS 1's
    assert LaserScan.model_validate_json(read["/scan"]) == scan
    assert Time.model_validate_json(read["/clock"]) == Time(sec=12, nanosec=2)
    assert TFMessage.model_validate_json(read["/tf"]) == TF


RANGE_JAZZY = """# Single range reading (Jazzy's definition: with variance)
uint8 ULTRASOUND=0
uint8 INFRARED=1
std_msgs/Header header
uint8 radiation_type
float32 field_of_view
float32 min_range
float32 max_range
float32 range
float32 variance
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""


CLOCK = "builtin_interfaces/Time clock\n" + "=" * 80 + "\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n"


def _foreign_bag(path: Path) -> Path:
    """A recording as a robot's `ros2 bag record` leaves it, written by mcap-ros2-support."""
    with path.open("wb") as stream:
        writer = Ros2Writer(stream)
        text = writer.register_msgdef("std_msgs/msg/String", "string data\n")
        sonar = writer.register_msgdef("sensor_msgs/msg/Range", RANGE_JAZZY)
        clock = writer.register_msgdef("rosgraph_msgs/msg/Clock", CLOCK)
        for i in range(5):
            writer.write_message("/chatter", text, {"data": f"hello {i}"}, log_time=START_NS + i * 10_000_000)
            writer.write_message("/clock", clock, {"clock": {"sec": 7, "nanosec": i}}, log_time=START_NS + i * 10_000_000 + 1)
        writer.write_message(
            "/sonar", sonar, {"header": {"stamp": {"sec": 7, "nanosec": 0}, "frame_id": "sonar"}, "radiation_type": 0,
                              "field_of_view": 0.5, "min_range": 0.1, "max_range": 4.0, "range": 1.25, "variance": 0.01},
            log_time=START_NS + 60_000_000,
        )
        writer.finish()
    return path


def test_a_recording_from_ros2_reads_as_skydeck_frames_and_bag_info_lists_it(tmp_path: Path) -> None:
    path = _foreign_bag(tmp_path / "robot.mcap")
    with BagReader(path) as bag:
        types = {t.topic: t.type_name for t in bag.summary.topics}
        assert types == {"/chatter": "std_msgs/msg/String", "/clock": "builtin_interfaces/msg/Time", "/sonar": "sensor_msgs/msg/Range"}
        read = [(m.topic, m.frame) for m in bag.messages()]
    assert [json.loads(f)["data"] for t, f in read if t == "/chatter"] == [f"hello {i}" for i in range(5)]
    assert [json.loads(f) for t, f in read if t == "/clock"][-1] == {"sec": 7, "nanosec": 4}
    (sonar,) = [Range.model_validate_json(f) for t, f in read if t == "/sonar"]  # Jazzy's variance left out
    assert (sonar.range, sonar.header.frame_id) == (1.25, "sonar")
    info = subprocess.run([sys.executable, "-m", "services.cli", "bag", "info", str(path)], capture_output=True, text=True, timeout=30, check=False)
    assert info.returncode == 0, info.stderr
    assert "/sonar" in info.stdout and "sensor_msgs/msg/Range" in info.stdout and "cdr" in info.stdout


async def test_a_recording_from_ros2_plays_into_skydeck(core, start_node, tmp_path: Path) -> None:
    from tests.conftest import wait_until

    path = _foreign_bag(tmp_path / "robot.mcap")
    listener = await start_node(lambda s: Listener(s, {"/chatter": String, "/sonar": Range}))
    await play(core, path, PlayOptions(wait_for_subscribers=True, topics=frozenset({"/chatter", "/sonar"})))
    await wait_until(lambda: len(listener.received) == 6, what="every message")
    assert [json.loads(f)["data"] for f in frames(listener, "/chatter")] == [f"hello {i}" for i in range(5)]
    assert Range.model_validate_json(frames(listener, "/sonar")[0]).range == 1.25


async def test_bag_record_encoding_cdr_writes_what_ros2_reads(core, start_node, tmp_path: Path) -> None:
    from tests.conftest import wait_until
    from tests.services.bag.test_record_play import Talker
    from tests.services.cli.test_bag_cli import linked_recorder, recorded

    talker = await start_node(Talker)
    process = await linked_recorder(core.url, talker, "/points", "--encoding", "cdr", "-o", str(tmp_path / "ros2"))
    try:
        talker.send(20)
        await wait_until(lambda: recorded(tmp_path / "ros2.mcap", "/points") == 20, timeout_s=20, what="20 on disk")
    finally:
        await asyncio.to_thread(process.stop, signal.SIGINT, 20)
    with (tmp_path / "ros2.mcap").open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        xs = [message.point.x for _, _, _, message in reader.iter_decoded_messages()]
    assert xs == [float(i) for i in range(20)]

