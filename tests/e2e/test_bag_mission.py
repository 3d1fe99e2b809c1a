"""Record the drone mission and play it back: the issue's end-to-end check of `skydeck bag`.

The mission is recorded for 20 s of sim time (`--speed max`) by `skydeck bag record` while a
separate subscriber counts the same topics; every recorded topic must be a run of what the
subscriber received, whole (count in = count in the file, same bytes, same order). The file
is then opened with the `mcap` library on its own, and played with `skydeck bag play` into a
fresh core, where a listener must get every recorded message again, in order, with the
recorded timing within a generous tolerance (timings are the benchmark's business).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import re
import sys
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader

from services.bag import BagReader
from services.launch.background import BackgroundProcess
from services.runtime import Node, NodeSettings
from shared_models import get_interface
from shared_models.builtin_interfaces import Time
from tests.conftest import CoreProcess, wait_until

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(240)]

SIM_SECONDS = 20.0
EXCLUDE = "^/simulator/camera(/.*)?$"  # rendered only while read: recording it would slow the world


class Counter(Node):
    """Keeps every frame of the topics it is given, as received, with its arrival time."""

    def __init__(self, settings: NodeSettings, topics: dict[str, str], name: str = "counter") -> None:
        super().__init__(name, settings=settings)
        self.frames: dict[str, list[tuple[str, float]]] = {topic: [] for topic in topics}
        for topic, type_name in topics.items():
            self.create_subscription(
                get_interface(type_name),
                topic,
                lambda frame, kept=self.frames[topic]: kept.append((frame, time.monotonic())),
                100_000,
                raw=True,
            )

    def texts(self, topic: str) -> list[str]:
        return [frame for frame, _ in self.frames[topic]]


def skydeck(*args: str, core_url: str, name: str) -> BackgroundProcess:
    env = {**os.environ, "SKYDECK_CORE_URL": core_url, "PYTHONUNBUFFERED": "1"}
    return BackgroundProcess([sys.executable, "-m", "services.cli", *args], name=name, env=env)


def contiguous_run(recorded: list[str], received: list[str]) -> bool:
    """Whether ``recorded`` appears in ``received`` as one unbroken run."""
    if not recorded:
        return True
    for start in (i for i, frame in enumerate(received) if frame == recorded[0]):
        if received[start : start + len(recorded)] == recorded:
            return True
    return False


async def test_record_the_mission_then_play_it_into_a_fresh_core(launch, tmp_path: Path) -> None:
    system = await launch("--speed", "max", "--seed", "21", "--boxes", "4", "start_mission:=true")
    graph = await system.graph()
    topics = {t["name"]: t["type"] for t in graph["topics"] if t["type"] and not re.search(EXCLUDE, t["name"])}
    assert {"/drone/pose", "/clock", "/simulator/boxes", "/drone/state"} <= set(topics)
    settings = NodeSettings(core_url=system.core_url, port=0)
    counter = Counter(settings, topics)
    await counter.start()
    path = tmp_path / "mission"
    recorder = skydeck("bag", "record", "-a", "-x", EXCLUDE, "-o", str(path), core_url=system.core_url, name="recorder")
    try:
        await recorder.await_line("subscribed to /drone/pose", 30)
        await recorder.await_line("subscribed to /clock", 30)
        await wait_until(lambda: len(counter.frames["/clock"]) > 0, 10, "the counter to get /clock")
        started = Time.model_validate_json(counter.frames["/clock"][-1][0]).to_sec()
        await wait_until(
            lambda: Time.model_validate_json(counter.frames["/clock"][-1][0]).to_sec() >= started + SIM_SECONDS + 10,  # the recorder links a moment after it subscribes: 3.4 sim s at --speed max on a fast machine
            timeout_s=120,
            what=f"{SIM_SECONDS:g} s of sim time",
        )
        assert await asyncio.to_thread(recorder.stop), recorder.tail()  # Ctrl-C: the file is finished
        assert recorder.returncode == 0, recorder.tail()
        # The counter outlives the recorder: keep it until its run covers the file's, every topic
        # (the checks below name a topic whose run it does not cover).
        bag_file = path.with_suffix(".mcap")
        with BagReader(bag_file) as bag:
            assert not bag.summary.recovered
            recorded = {t.topic: [m.frame for m in bag.messages([t.topic])] for t in bag.summary.topics}
            assert bag.summary.metadata["skydeck"]["world_seed"] == "21"
        with contextlib.suppress(AssertionError):
            await wait_until(
                lambda: all(contiguous_run(frames, counter.texts(t)) for t, frames in recorded.items()),
                timeout_s=30,
                what="the counter to receive what the file holds",
            )
    finally:
        recorder.stop()
        await counter.stop()
    assert not any("Traceback" in line for line in recorder.lines), recorder.tail()

    # `bag info` counts = the counter's counts over the same span; the same frames, in order.
    info = skydeck("bag", "info", str(bag_file), core_url=system.core_url, name="info")
    await asyncio.to_thread(info.popen.wait, 30)
    counts = {m.group(1): int(m.group(2)) for line in info.lines if (m := re.search(r"Topic: (\S+) \|.*Count: (\d+)", line))}
    assert counts.keys() == recorded.keys()  # info lists every topic of the file
    for topic, frames in recorded.items():
        assert counts[topic] == len(frames)
        assert contiguous_run(frames, counter.texts(topic)), f"{topic}: the file is not a run of what was received"
    poses = [json.loads(frame)["header"] for frame in recorded["/drone/pose"]]
    assert [h["seq"] for h in poses] == list(range(poses[0]["seq"], poses[0]["seq"] + len(poses)))  # none lost
    sim_span = Time.model_validate(poses[-1]["stamp"]).to_sec() - Time.model_validate(poses[0]["stamp"]).to_sec()
    assert sim_span >= SIM_SECONDS, sim_span

    # The mcap library reads it on its own: a schema, named by the ROS type, for every channel.
    with open(bag_file, "rb") as stream:
        summary = make_reader(stream).get_summary()
    assert summary is not None
    for channel in summary.channels.values():
        schema = summary.schemas[channel.schema_id]
        assert (channel.message_encoding, schema.encoding) == ("json", "jsonschema")
        assert schema.name == topics[channel.topic]

    # Played into a fresh core: the same messages, in the same order, with the recorded timing.
    fresh = CoreProcess()
    await fresh.start()
    listener = Counter(NodeSettings(core_url=fresh.url, port=0), {t: topics[t] for t in recorded}, name="listener")
    await listener.start()
    try:
        player = skydeck("bag", "play", str(bag_file), "--wait-for-subscribers", core_url=fresh.url, name="player")
        assert await asyncio.to_thread(player.popen.wait, 120) == 0, player.tail()
        expected = sum(len(frames) for frames in recorded.values())
        await wait_until(lambda: sum(len(f) for f in listener.frames.values()) >= expected, 10, "every message played")
    finally:
        await listener.stop()
        await fresh.stop()
    for topic, frames in recorded.items():
        assert listener.texts(topic) == frames, topic
    with BagReader(bag_file) as bag:
        log_times = [m.log_time_ns / 1e9 for m in bag.messages(["/drone/pose"])]
    arrivals = [t for _, t in listener.frames["/drone/pose"]]
    recorded_span, played_span = log_times[-1] - log_times[0], arrivals[-1] - arrivals[0]
    assert abs(played_span - recorded_span) < 0.25 * recorded_span + 0.5, (played_span, recorded_span)
