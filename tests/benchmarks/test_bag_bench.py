"""The recording benchmark's arithmetic: how many messages a topic published while recorded."""

from __future__ import annotations

from pathlib import Path

from benchmarks.bag import _kept, _timing_bag
from services.bag import BagReader, BagWriter
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import PointStamped
from shared_models.std_msgs import Header


def test_kept_counts_gaps_in_seq_and_in_clock_steps(tmp_path: Path) -> None:
    writer = BagWriter.create(tmp_path / "gaps.mcap", metadata={})
    points = writer.add_topic("/points", "geometry_msgs/msg/PointStamped")
    clock = writer.add_topic("/clock", "builtin_interfaces/msg/Time")
    text = writer.add_topic("/text", "std_msgs/msg/String")
    for i, seq in enumerate([5, 6, 7, 9, 10]):  # 8 lost: 5 of 6
        writer.write(points, PointStamped(header=Header(seq=seq)).model_dump_json(), 1_000 + i)
    for i, step in enumerate([0, 1, 2, 3, 5, 6, 7]):  # one 1/60 s step lost: 7 of 8
        writer.write(clock, Time.from_sec(step / 60).model_dump_json(), 2_000 + i)
    writer.write(text, '{"data":"a"}', 3_000)
    writer.write(text, '{"data":"b"}', 3_001)
    writer.close()
    with BagReader(tmp_path / "gaps.mcap") as bag:
        assert _kept(bag, "/points") == 5 / 6
        assert _kept(bag, "/clock") == 7 / 8
        assert _kept(bag, "/text") is None  # nothing says how many were published


def test_the_timing_recording_interleaves_two_rates(tmp_path: Path) -> None:
    with BagReader(_timing_bag(tmp_path / "t.mcap", 1.0)) as bag:
        counts = {topic.topic: topic.count for topic in bag.summary.topics}
        times = [message.log_time_ns for message in bag.messages()]
    assert counts == {"/bench/fast": 100, "/bench/slow": 30} and times == sorted(times)
