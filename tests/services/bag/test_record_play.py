"""The recorder and the player as nodes in a real graph: a real core, real sockets, in-process."""

from __future__ import annotations

import asyncio
import re
import sys
import threading
import time
from pathlib import Path

import pytest

from services.bag import (
    BagError,
    BagReader,
    BagWriter,
    Limits,
    Player,
    PlayOptions,
    Recorder,
    TopicSelection,
    check_types,
)
from services.runtime import Node
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, PointStamped
from shared_models.std_msgs import Header, String
from tests.conftest import wait_until

START_NS = 1_700_000_000_000_000_000


class Talker(Node):
    """Publishes on demand, so a test knows exactly what went out."""

    def __init__(self, settings, name: str = "talker", topic: str = "/points") -> None:
        super().__init__(name, settings=settings)
        self.publisher = self.create_publisher(PointStamped, topic, 10)
        self.strings = self.create_publisher(String, topic + "_text", 10)

    def send(self, count: int) -> None:
        for i in range(count):
            self.publisher.publish(PointStamped(header=Header(frame_id="map"), point=Point(x=float(i))))


class Listener(Node):
    """Keeps every frame of its topics, with the time it arrived."""

    def __init__(self, settings, topics: dict[str, type], *, use_sim_time: bool = False) -> None:
        if use_sim_time:
            settings = settings.model_copy(update={"use_sim_time": True})
        super().__init__("listener", settings=settings)
        self.received: list[tuple[str, str, float]] = []
        for topic in topics:
            self.create_subscription(
                topics[topic], topic, lambda frame, t=topic: self.received.append((t, frame, time.monotonic())), 10_000, raw=True
            )


def frames(listener: Listener, topic: str) -> list[str]:
    return [frame for name, frame, _ in listener.received if name == topic]


async def test_the_recorder_picks_up_topics_that_appear_later_and_writes_frames_as_sent(core, start_node, tmp_path: Path) -> None:
    writer = BagWriter.create(tmp_path / "run.mcap", metadata={})
    recorder = await start_node(lambda s: Recorder(writer, TopicSelection(all_topics=True, exclude=re.compile("_text$")), settings=s))
    listener = await start_node(lambda s: Listener(s, {"/points": PointStamped}))
    talker = await start_node(Talker)  # after the recorder: -a finds it in the graph
    await wait_until(lambda: "/points" in recorder.recording.topics, what="the recorder to subscribe")
    await wait_until(lambda: talker.publisher.get_subscription_count() == 2, what="both readers to link")
    talker.send(500)
    talker.strings.publish(String(data="left out"))
    await wait_until(lambda: writer.counts().get("/points") == 500 and len(listener.received) == 500, what="500 recorded")
    graph = core.registry.graph()
    assert recorder.get_name() in {node["name"] for node in graph["nodes"]}
    await recorder.stop()
    writer.close()
    with BagReader(writer.path) as bag:
        assert bag.summary.topic("/points_text") is None  # --exclude
        recorded = [message.frame for message in bag.messages(["/points"])]
    assert recorded == frames(listener, "/points")  # the same bytes, the same order


async def test_named_topics_only_and_a_topic_named_before_it_exists(core, start_node, tmp_path: Path) -> None:
    writer = BagWriter.create(tmp_path / "run.mcap", metadata={})
    said: list[str] = []
    recorder = await start_node(
        lambda s: Recorder(writer, TopicSelection(topics=frozenset({"/points_text"})), settings=s, say=said.append)
    )
    await wait_until(lambda: any("waiting for /points_text" in line for line in said), what="the waiting line")
    talker = await start_node(Talker)
    await wait_until(lambda: talker.strings.get_subscription_count() == 1, what="the recorder to link")
    talker.send(10)
    talker.strings.publish(String(data="kept"))
    await wait_until(lambda: writer.counts().get("/points_text") == 1, what="the string recorded")
    await recorder.stop()
    writer.close()
    with BagReader(writer.path) as bag:
        assert [t.topic for t in bag.summary.topics] == ["/points_text"]


async def test_the_recorder_stops_by_itself_at_its_limits(core, start_node, tmp_path: Path) -> None:
    said: list[str] = []
    writer = BagWriter.create(tmp_path / "short.mcap", metadata={})
    recorder = Recorder(writer, TopicSelection(all_topics=True), limits=Limits(duration_s=0.3), settings=_settings(core), say=said.append)
    async with asyncio.timeout(10):
        await recorder.run_until_stopped()
    writer.close()
    assert "stopping: --max-duration 0.3 s reached" in said

    talker = await start_node(Talker)
    writer = BagWriter.create(tmp_path / "small.mcap", metadata={})
    recorder = Recorder(writer, TopicSelection(topics=frozenset({"/points"})), limits=Limits(size_bytes=20_000), settings=_settings(core), say=said.append)
    run = asyncio.ensure_future(recorder.run_until_stopped())
    await wait_until(lambda: talker.publisher.get_subscription_count() == 1, what="the recorder to link")
    async with asyncio.timeout(20):
        while not run.done():
            talker.send(500)
            await asyncio.sleep(0.05)
    writer.close()
    assert "stopping: --max-size 0.02 MB reached" in said and writer.path.stat().st_size >= 20_000


def _settings(core):  # type: ignore[no-untyped-def]
    from services.runtime import NodeSettings

    return NodeSettings(core_url=core.url, port=0)


# -- playing --------------------------------------------------------------------------------


def point_frame(i: int) -> str:
    return PointStamped(header=Header(seq=i + 1, stamp=Time(sec=100 + i), frame_id="map"), point=Point(x=float(i))).model_dump_json()


def make_bag(path: Path, *, count: int = 50, period_ns: int = 20_000_000, with_clock: bool = False) -> Path:
    writer = BagWriter.create(path, metadata={})
    points = writer.add_topic("/points", "geometry_msgs/msg/PointStamped")
    text = writer.add_topic("/text", "std_msgs/msg/String", latched=True)
    clock = writer.add_topic("/clock", "builtin_interfaces/msg/Time") if with_clock else None
    for i in range(count):
        writer.write(points, point_frame(i), START_NS + i * period_ns)
        if clock is not None:
            writer.write(clock, Time(sec=100 + i).model_dump_json(), START_NS + i * period_ns + 1)
    writer.write(text, String(data="end").model_dump_json(), START_NS + count * period_ns)
    writer.close()
    return path


async def play(core, bag_path: Path, options: PlayOptions, *, timeout_s: float = 20.0) -> Player:  # type: ignore[no-untyped-def]
    with BagReader(bag_path) as reader:
        player = Player(reader, options, settings=_settings(core))
        async with asyncio.timeout(timeout_s):
            await player.run_until_stopped()
    return player


async def test_play_replays_the_same_frames_in_order_with_the_recorded_timing(core, start_node, tmp_path: Path) -> None:
    path = make_bag(tmp_path / "run.mcap", count=50, period_ns=20_000_000)  # 1 s
    listener = await start_node(lambda s: Listener(s, {"/points": PointStamped, "/text": String}))
    player = await play(core, path, PlayOptions(wait_for_subscribers=True))
    await wait_until(lambda: len(listener.received) == 51, what="every message")
    assert frames(listener, "/points") == [point_frame(i) for i in range(50)]
    assert [name for name, _, _ in listener.received][-1] == "/text"
    arrivals = [t for name, _, t in listener.received if name == "/points"]
    assert 0.7 < arrivals[-1] - arrivals[0] < 3.0  # 0.98 s recorded; generous: a shared machine
    assert player.played == 51

    listener.received.clear()
    await play(core, path, PlayOptions(rate=4.0, topics=frozenset({"/points"}), wait_for_subscribers=True))
    await wait_until(lambda: len(listener.received) == 50, what="the /points messages")
    arrivals = [t for _, _, t in listener.received]
    assert arrivals[-1] - arrivals[0] < 0.7  # a quarter of 0.98 s
    assert not frames(listener, "/text")  # --topics


async def test_start_offset_remap_and_loop(core, start_node, tmp_path: Path) -> None:
    path = make_bag(tmp_path / "run.mcap", count=50, period_ns=10_000_000)
    listener = await start_node(lambda s: Listener(s, {"/moved": PointStamped}))
    await play(
        core,
        path,
        PlayOptions(start_offset_s=0.3, remap={"/points": "/moved"}, topics=frozenset({"/points"}), wait_for_subscribers=True),
    )
    await wait_until(lambda: len(listener.received) == 20, what="the last 20 messages")
    assert frames(listener, "/moved") == [point_frame(i) for i in range(30, 50)]

    listener.received.clear()
    with BagReader(path) as reader:
        player = Player(reader, PlayOptions(loop=True, rate=10.0, topics=frozenset({"/points"}), remap={"/points": "/moved"}, wait_for_subscribers=True), settings=_settings(core))
        run = asyncio.ensure_future(player.run_until_stopped())
        await wait_until(lambda: player.played > 120, timeout_s=20, what="the recording played more than twice")
        player.destroy_node()
        await run
    assert frames(listener, "/moved")[50:55] == [point_frame(i) for i in range(5)]  # from the start again


async def test_clock_from_receive_times_drives_a_sim_time_node(core, start_node, tmp_path: Path) -> None:
    path = make_bag(tmp_path / "run.mcap", count=50, period_ns=20_000_000)
    listener = await start_node(lambda s: Listener(s, {"/clock": Time}, use_sim_time=True))
    with BagReader(path) as reader:
        player = Player(reader, PlayOptions(clock=True, topics=frozenset({"/points"})), settings=_settings(core))
        assert "/clock" in player.describe().model_dump_json()
        async with asyncio.timeout(20):
            await player.run_until_stopped()
    await wait_until(lambda: len(listener.received) > 5, what="/clock messages")
    ticks = [Time.model_validate_json(frame).to_nsec() for _, frame, _ in listener.received]
    assert all(START_NS <= tick <= START_NS + 1_000_000_000 for tick in ticks) and ticks == sorted(ticks)
    assert START_NS <= listener.get_clock().now().nanoseconds <= START_NS + 1_000_000_000


async def test_clock_from_a_recorded_clock_topic_is_that_topic(core, start_node, tmp_path: Path) -> None:
    path = make_bag(tmp_path / "run.mcap", count=30, period_ns=10_000_000, with_clock=True)
    listener = await start_node(lambda s: Listener(s, {"/clock": Time}, use_sim_time=True))
    await play(core, path, PlayOptions(clock=True, topics=frozenset({"/clock"}), wait_for_subscribers=True))
    await wait_until(lambda: len(listener.received) == 30, what="the recorded /clock")
    assert [Time.model_validate_json(f).sec for _, f, _ in listener.received] == list(range(100, 130))
    assert listener.get_clock().now().nanoseconds == 129 * 10**9


async def test_pause_holds_the_timeline_and_resume_goes_on(core, start_node, tmp_path: Path) -> None:
    path = make_bag(tmp_path / "run.mcap", count=50, period_ns=20_000_000)
    said: list[str] = []
    with BagReader(path) as reader:
        player = Player(reader, PlayOptions(), settings=_settings(core), say=said.append)
        run = asyncio.ensure_future(player.run_until_stopped())
        await wait_until(lambda: player.played >= 5, what="some messages played")
        player.toggle_pause()
        held = player.played
        await asyncio.sleep(0.3)  # a paused player must publish nothing over this span
        assert player.played == held and player.paused and said[-1].startswith("[PAUSED]")
        player.toggle_pause()
        async with asyncio.timeout(20):
            await run
    assert player.played == 51 and said[-1].startswith("[RUNNING]")


async def test_what_cannot_be_played_is_one_clear_error(core, tmp_path: Path) -> None:
    path = make_bag(tmp_path / "run.mcap")
    with BagReader(path) as reader:
        with pytest.raises(BagError, match="has no topic /nope"):
            Player(reader, PlayOptions(topics=frozenset({"/nope"})))
        with pytest.raises(BagError, match="past the end"):
            Player(reader, PlayOptions(start_offset_s=60))
        with pytest.raises(BagError, match="--remap names /nope"):
            Player(reader, PlayOptions(remap={"/nope": "/x"}))
    with pytest.raises(BagError, match="--rate"):
        PlayOptions(rate=0)
    with pytest.raises(BagError, match="/points is std_msgs/msg/String in the running system"):
        check_types([{"name": "/points", "type": "std_msgs/msg/String"}], {"/points": "geometry_msgs/msg/PointStamped"})
    check_types([{"name": "/points", "type": "geometry_msgs/msg/PointStamped"}], {"/points": "geometry_msgs/msg/PointStamped"})


async def test_a_message_handed_over_as_a_pause_comes_waits_for_the_resume(core, tmp_path: Path) -> None:
    """The timeline thread may hand a message to the loop just before a pause: it is held, not
    published, and goes out first on resume (a paused player publishes nothing)."""
    path = make_bag(tmp_path / "run.mcap", count=3)
    with BagReader(path) as reader:
        player = Player(reader, PlayOptions(), settings=_settings(core))
        first = next(reader.messages(["/points"]))
        player.pause()
        player._publish(first, due_s=time.perf_counter())
        assert player.played == 0
        player.resume()
        assert player.played == 1 and player.position_s == 0.0


@pytest.mark.parametrize("paused", [False, True], ids=["waiting", "paused"])
async def test_ctrl_c_ends_the_timeline_thread_waiting_for_a_far_message_or_paused(core, tmp_path: Path, paused: bool) -> None:
    """The next message is 1,000 s away; cancelling the player (Ctrl-C) wakes its timeline thread,
    which ends (it reads the file) before the player does."""
    path = make_bag(tmp_path / "run.mcap", count=2, period_ns=1000 * 10**9)
    with BagReader(path) as reader:
        player = Player(reader, PlayOptions(), settings=_settings(core))
        run = asyncio.ensure_future(player.run_until_stopped())
        await wait_until(lambda: player.played == 1, what="the first message")
        assert _in_timeline()
        if paused:
            player.pause()
        run.cancel()
        async with asyncio.timeout(10):
            await asyncio.gather(run, return_exceptions=True)
    assert player.played == 1 and not _in_timeline()


def _in_timeline() -> bool:
    """Whether some thread is running a player's timeline now."""
    for frame in sys._current_frames().values():
        while frame is not None:
            if frame.f_code is Player._timeline.__code__:
                return True
            frame = frame.f_back  # type: ignore[assignment]
    return False


def test_a_stop_that_comes_just_before_the_timeline_waits_is_not_lost(core, tmp_path: Path) -> None:
    """The thread clears its wake-up before it looks at the player's state, so a stop (or a pause)
    that lands between its look and its wait still ends the wait, however far off the message is."""
    path = make_bag(tmp_path / "run.mcap", count=3)
    with BagReader(path) as reader:
        player = Player(reader, PlayOptions(), settings=_settings(core))

        class StopJustBeforeClear(threading.Event):
            def clear(self) -> None:
                player._ending.set()  # what stop does: ending, then the wake-up
                self.set()
                super().clear()

        player._wake = StopJustBeforeClear()
        result: list[bool] = []
        waiting = threading.Thread(target=lambda: result.append(player._wait_until(time.perf_counter() + 1000)), daemon=True)
        waiting.start()
        waiting.join(timeout=10)
    assert result == [False]
