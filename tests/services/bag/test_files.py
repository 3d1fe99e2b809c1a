"""Recordings as files: written by BagWriter, read back by BagReader and by the mcap library
on its own, and read again after being cut short (a killed recorder)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from mcap.reader import make_reader

from services.bag import BagError, BagFileError, BagReader, BagWriter, bag_path, format_info
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, Pose, PoseStamped
from shared_models.std_msgs import Header

START_NS = 1_700_000_000_000_000_000


def pose_frame(seq: int) -> str:
    header = Header(seq=seq, stamp=Time(sec=seq, nanosec=500), frame_id="map")
    return PoseStamped(header=header, pose=Pose(position=Point(x=float(seq)))).model_dump_json()


def write_bag(path: Path, count: int, *, flush_every: int = 0) -> None:
    writer = BagWriter.create(path, metadata={"command_line": "test", "world_seed": "7"})
    pose = writer.add_topic("/drone/pose", "geometry_msgs/msg/PoseStamped")
    clock = writer.add_topic("/clock", "builtin_interfaces/msg/Time", latched=True)
    for i in range(count):
        writer.write(pose, pose_frame(i), START_NS + i * 10_000_000)
        writer.write(clock, Time(sec=i).model_dump_json(), START_NS + i * 10_000_000 + 1)
        if flush_every and i % flush_every == flush_every - 1:
            writer.flush()
    writer.close()


def test_a_recording_reads_back_in_order_with_receive_time_stamp_and_seq(tmp_path: Path) -> None:
    path = tmp_path / "run.mcap"
    write_bag(path, 300)
    with BagReader(path) as bag:
        summary = bag.summary
        assert summary.message_count == 600 and not summary.recovered
        assert (summary.start_ns, summary.end_ns) == (START_NS, START_NS + 299 * 10_000_000 + 1)
        assert {t.topic: (t.type_name, t.count, t.latched) for t in summary.topics} == {
            "/clock": ("builtin_interfaces/msg/Time", 300, True),
            "/drone/pose": ("geometry_msgs/msg/PoseStamped", 300, False),
        }
        assert summary.metadata["skydeck"]["world_seed"] == "7"
        poses = list(bag.messages(["/drone/pose"]))
        assert [m.frame for m in poses] == [pose_frame(i) for i in range(300)]
        assert poses[5].publish_time_ns == 5 * 10**9 + 500 and poses[5].sequence == 5  # the header's
        clocks = list(bag.messages(["/clock"]))
        assert clocks[3].publish_time_ns == clocks[3].log_time_ns  # no header: the receive time
        later = list(bag.messages(start_ns=START_NS + 100 * 10_000_000))
        assert len(later) == 400 and later[0].frame == pose_frame(100)
        times = [m.log_time_ns for m in bag.messages()]
        assert times == sorted(times)


def test_the_mcap_library_reads_schemas_channels_and_metadata_on_its_own(tmp_path: Path) -> None:
    path = tmp_path / "run.mcap"
    write_bag(path, 50)
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        summary = reader.get_summary()
        assert summary is not None and reader.get_header().profile == ""
        schemas = {schema.name: schema for schema in summary.schemas.values()}
        assert set(schemas) == {"geometry_msgs/msg/PoseStamped", "builtin_interfaces/msg/Time"}
        pose_schema = schemas["geometry_msgs/msg/PoseStamped"]
        assert pose_schema.encoding == "jsonschema"
        schema = json.loads(pose_schema.data)
        assert "$ref" not in pose_schema.data.decode() and "$defs" not in schema  # self-contained
        stamp = schema["properties"]["header"]["properties"]["stamp"]["properties"]
        assert set(stamp) == {"sec", "nanosec", "nsec"}  # ROS 2's name and Foxglove's
        channels = {channel.topic: channel for channel in summary.channels.values()}
        assert {c.message_encoding for c in channels.values()} == {"json"}
        assert summary.schemas[channels["/drone/pose"].schema_id].name == "geometry_msgs/msg/PoseStamped"
        assert summary.statistics.channel_message_counts[channels["/drone/pose"].id] == 50
        messages = list(reader.iter_messages(topics=["/drone/pose"]))
        assert PoseStamped.model_validate_json(messages[7][2].data).header.seq == 7
        assert [m.name for m in reader.iter_metadata()] == ["skydeck"]


def test_the_mcap_library_checks_every_crc_and_index_of_a_file_of_many_chunks(tmp_path: Path) -> None:
    """Skydeck writes MCAP's records itself (services.bag.mcap_file): the library's three readers
    agree with it, checksums checked, also for a topic that first appears after some chunks."""
    from mcap.reader import NonSeekingReader, SeekingReader
    from mcap.stream_reader import StreamReader

    path = tmp_path / "many.mcap"
    writer = BagWriter.create(path, metadata={"command_line": "test"})
    pose = writer.add_topic("/drone/pose", "geometry_msgs/msg/PoseStamped")
    for i in range(4000):
        writer.write(pose, pose_frame(i), START_NS + i)
        if i == 1000:
            writer.flush()
            late = writer.add_topic("/late", "std_msgs/msg/String")
        if i > 1000 and i % 4 == 0:
            writer.write(late, '{"data":"x"}', START_NS + i)
    writer.close()
    with open(path, "rb") as stream:
        reader = SeekingReader(stream, validate_crcs=True)
        summary = reader.get_summary()
        assert summary is not None and summary.statistics is not None
        assert len(summary.chunk_indexes) >= 2 and summary.statistics.chunk_count == len(summary.chunk_indexes)
        counts = {summary.channels[c].topic: n for c, n in summary.statistics.channel_message_counts.items()}
        assert counts == {"/drone/pose": 4000, "/late": 749} and summary.statistics.message_count == 4749
        assert (summary.statistics.message_start_time, summary.statistics.message_end_time) == (START_NS, START_NS + 3999)
        in_order = [message.log_time for _, _, message in reader.iter_messages(log_time_order=True)]
        assert len(in_order) == 4749 and in_order == sorted(in_order)
        late_ones = list(reader.iter_messages(topics=["/late"], starting_at=START_NS + 2000))
        assert len(late_ones) == 500
    with open(path, "rb") as stream:
        assert sum(1 for _ in NonSeekingReader(stream, validate_crcs=True).iter_messages()) == 4749
    with open(path, "rb") as stream:
        kinds = [type(record).__name__ for record in StreamReader(stream, validate_crcs=True).records]
    assert kinds[:3] == ["Header", "Metadata", "Schema"] and kinds[-1] == "Footer"


def test_bytes_are_base64_in_the_schema_as_foxglove_decodes_them(tmp_path: Path) -> None:
    from services.bag.schemas import schema_bytes

    schema = json.loads(schema_bytes("sensor_msgs/msg/CompressedImage"))
    assert schema["title"] == "sensor_msgs/msg/CompressedImage"
    assert schema["properties"]["data"] == {**schema["properties"]["data"], "type": "string", "contentEncoding": "base64"}


@pytest.mark.parametrize("keep", [0.35, 0.5, 0.8, 0.9])
def test_a_file_cut_mid_chunk_reads_up_to_its_last_complete_chunk(tmp_path: Path, keep: float) -> None:
    whole = tmp_path / "whole.mcap"
    write_bag(whole, 3000, flush_every=250)  # a chunk every 500 messages, as the recorder flushes
    data = whole.read_bytes()
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(data[: int(len(data) * keep)])
    with BagReader(cut) as bag:
        summary = bag.summary
        assert summary.recovered and summary.ignored_bytes > 0
        assert summary.message_count % 500 == 0 and 0 < summary.message_count < 6000
        messages = list(bag.messages())
        assert len(messages) == summary.message_count
        poses = [m for m in messages if m.topic == "/drone/pose"]
        assert [m.frame for m in poses] == [pose_frame(i) for i in range(len(poses))]  # a prefix, whole
        assert "not finished" in format_info(summary)


def test_a_file_cut_in_its_summary_keeps_every_message(tmp_path: Path) -> None:
    whole = tmp_path / "whole.mcap"
    write_bag(whole, 1000, flush_every=250)
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(whole.read_bytes()[:-40])  # the footer and part of the summary gone
    with BagReader(cut) as bag:
        assert bag.summary.recovered and bag.summary.message_count == 2000
        assert len(list(bag.messages(["/clock"]))) == 1000


def test_a_file_cut_before_any_chunk_or_not_mcap_is_one_clear_error(tmp_path: Path) -> None:
    whole = tmp_path / "whole.mcap"
    write_bag(whole, 100)
    head = tmp_path / "head.mcap"
    head.write_bytes(whole.read_bytes()[:60])
    with pytest.raises(BagFileError, match="no complete chunk"):
        BagReader(head)
    text = tmp_path / "notes.mcap"
    text.write_text("hello")
    with pytest.raises(BagFileError, match="not an MCAP recording"):
        BagReader(text)
    with pytest.raises(BagFileError, match="no such file"):
        BagReader(tmp_path / "missing.mcap")
    with pytest.raises(BagFileError, match="folder"):
        BagReader(tmp_path)


def test_a_writer_never_overwrites_and_says_why_it_cannot_write(tmp_path: Path) -> None:
    write_bag(tmp_path / "run.mcap", 1)
    with pytest.raises(BagError, match="already exists"):
        BagWriter.create(tmp_path / "run.mcap", metadata={})
    with pytest.raises(BagError, match="does not exist"):
        BagWriter.create(tmp_path / "no" / "run.mcap", metadata={})
    if os.geteuid() != 0:  # root writes anywhere
        locked = tmp_path / "locked"
        locked.mkdir(mode=0o500)
        with pytest.raises(BagError, match="cannot write"):
            BagWriter.create(locked / "run.mcap", metadata={})
    writer = BagWriter.create(tmp_path / "types.mcap", metadata={})
    with pytest.raises(BagError, match="unknown interface"):
        writer.add_topic("/x", "nope_msgs/msg/Nothing")
    writer.add_topic("/x", "std_msgs/msg/String")
    with pytest.raises(BagError, match="recorded as std_msgs/msg/String"):
        writer.add_topic("/x", "std_msgs/msg/Bool")
    writer.close()


def test_bag_path_adds_the_extension_once() -> None:
    assert bag_path("run") == Path("run.mcap")
    assert bag_path("dir/run.mcap") == Path("dir/run.mcap")
    assert bag_path("run.v2") == Path("run.v2.mcap")


def test_frames_from_other_clients_still_give_their_stamp(tmp_path: Path) -> None:
    path = tmp_path / "spaced.mcap"
    writer = BagWriter.create(path, metadata={})
    channel = writer.add_topic("/p", "geometry_msgs/msg/PointStamped")
    spaced = '{"point": {"x": 1}, "header": {"stamp": {"nanosec": 2, "sec": 3}, "seq": 9, "frame_id": ""}}'
    writer.write(channel, spaced, START_NS)
    writer.write(channel, "{}", START_NS + 1)  # no header at all: the receive time
    writer.close()
    with BagReader(path) as bag:
        first, second = bag.messages()
    assert (first.publish_time_ns, first.sequence, first.frame) == (3 * 10**9 + 2, 9, spaced)
    assert second.publish_time_ns == START_NS + 1
