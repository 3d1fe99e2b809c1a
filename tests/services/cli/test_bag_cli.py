"""`skydeck bag record | info | play` as a user runs them: subprocesses, Ctrl-C, a killed
recorder, and one clear line for every bad input."""

from __future__ import annotations

import asyncio
import os
import re
import signal
import sys
from pathlib import Path

import pytest

from services.bag import BagFileError, BagReader
from services.launch.background import BackgroundProcess
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import PointStamped
from tests.conftest import free_port, wait_until
from tests.services.bag.test_record_play import Listener, Talker, frames, make_bag, point_frame
from tests.services.cli.test_cli import skydeck


def recorder(core_url: str, *args: str) -> BackgroundProcess:
    env = {**os.environ, "SKYDECK_CORE_URL": core_url, "PYTHONUNBUFFERED": "1"}
    return BackgroundProcess([sys.executable, "-m", "services.cli", "bag", "record", *args], name="recorder", env=env)


async def linked_recorder(core_url: str, talker: Talker, *args: str) -> BackgroundProcess:
    """``skydeck bag record ARGS``, returned once the talker's /points is linked to it."""
    process = recorder(core_url, *args)
    await process.await_line("subscribed to /points", 30)
    async with asyncio.timeout(20):
        while talker.publisher.get_subscription_count() < 1:
            await asyncio.sleep(0.02)
    return process


async def test_ctrl_c_finishes_the_file_and_info_prints_it(core, start_node, tmp_path: Path) -> None:
    talker = await start_node(Talker)
    process = recorder(core.url, "/points", "/points_text", "-o", str(tmp_path / "run"))
    try:
        await process.await_line("subscribed to /points_text", 30)
        async with asyncio.timeout(20):
            while talker.publisher.get_subscription_count() < 1 or talker.strings.get_subscription_count() < 1:
                await asyncio.sleep(0.02)
        talker.send(100)
        # All 100 on disk (the recorder flushes a chunk every second), then Ctrl-C.
        await wait_until(lambda: recorded(tmp_path / "run.mcap", "/points") == 100, timeout_s=20, what="100 messages on disk")
        assert await asyncio.to_thread(process.stop, signal.SIGINT, 20)
    finally:
        process.stop()
    assert process.returncode == 0 and any("recorded 100 messages on 2 topics" in line for line in process.lines), process.tail()
    status, out, err = await skydeck(core.url, "bag", "info", str(tmp_path / "run.mcap"))
    assert status == 0 and err == ""
    assert "Messages:          100" in out and "Storage id:        mcap" in out
    assert "Topic: /points | Type: geometry_msgs/msg/PointStamped | Count: 100 | Rate:" in out
    assert "Topic: /points_text | Type: std_msgs/msg/String | Count: 0" in out
    assert "Command line:      skydeck bag record /points /points_text -o" in out
    assert re.search(r"^Skydeck:\s+\d", out, re.MULTILINE)  # the version that recorded it


def recorded(path: Path, topic: str) -> int:
    """Messages of ``topic`` readable in ``path`` now (0 while no chunk is complete)."""
    try:
        with BagReader(path) as bag:
            found = bag.summary.topic(topic)
    except BagFileError:
        return 0
    return found.count if found is not None else 0


async def test_a_killed_recorder_leaves_a_file_info_and_play_still_read(core, start_node, tmp_path: Path) -> None:
    talker = await start_node(Talker)
    process = await linked_recorder(core.url, talker, "-a", "-o", str(tmp_path / "killed.mcap"))
    try:
        talker.send(300)
        path = tmp_path / "killed.mcap"
        await wait_until(lambda: recorded(path, "/points") == 300, timeout_s=20, what="the chunk on disk")  # within a second
    finally:
        process.stop(signal.SIGKILL)
    with BagReader(path) as bag:
        assert bag.summary.recovered and bag.summary.topic("/points").count == 300
    status, out, err = await skydeck(core.url, "bag", "info", str(path))
    assert status == 0 and "Count: 300" in out and "not finished" in out
    assert err.startswith("skydeck: warning:") and err.count("\n") == 1
    status, out, err = await skydeck(core.url, "bag", "play", str(path), "--topics", "/points", "--rate", "100")
    assert status == 0 and "played 300 messages" in out, err


async def test_record_limits_stop_it_by_itself(core, start_node, tmp_path: Path) -> None:
    status, out, _ = await skydeck(core.url, "bag", "record", "-a", "--max-duration", "0.5", "-o", str(tmp_path / "d"))
    assert status == 0 and "stopping: --max-duration 0.5 s reached" in out and (tmp_path / "d.mcap").is_file()
    talker = await start_node(Talker)

    async def flood() -> None:
        while True:
            talker.send(200)
            await asyncio.sleep(0.02)

    flooding = asyncio.ensure_future(flood())
    try:
        status, out, _ = await skydeck(
            core.url, "bag", "record", "/points", "--max-size", "0.05", "-x", "text", "-o", str(tmp_path / "s"), timeout_s=60
        )
    finally:
        flooding.cancel()
    assert status == 0 and "stopping: --max-size 0.05 MB reached" in out
    assert (tmp_path / "s.mcap").stat().st_size >= 50_000


async def test_play_with_its_flags_through_the_cli(core, tmp_path: Path) -> None:
    path = make_bag(tmp_path / "run.mcap", count=40, period_ns=10_000_000)
    status, out, err = await skydeck(
        core.url, "bag", "play", str(path), "-r", "2", "--start-offset", "0.2", "--topics", "/points",
        "--remap", "/points:=/replayed", "--clock", "--clock-hz", "50",
    )
    assert status == 0, err
    assert "on 1 topics" in out and "played 20 messages" in out

    env = {**os.environ, "SKYDECK_CORE_URL": core.url, "PYTHONUNBUFFERED": "1"}
    looping = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "bag", "play", str(path), "-l", "--topics", "/points", "-r", "20"],
        name="player", env=env,
    )

    def published() -> int:
        counts = [record.counters.get("/points", (0,))[0] for name, record in core.registry.nodes.items() if name.startswith("/bag_play_")]
        return max(counts, default=0)

    try:
        await wait_until(lambda: published() > 45, timeout_s=30, what="a second pass")  # 40 messages a pass
        assert await asyncio.to_thread(looping.stop, signal.SIGINT, 20)
    finally:
        looping.stop()
    played = int(next(line for line in looping.lines if line.startswith("played")).split()[1])
    assert looping.returncode == 0 and played > 45


async def test_play_clock_publishes_the_recorded_clock_that_topics_leaves_out(core, start_node, tmp_path: Path) -> None:
    """`bag play --clock --topics /points` of a recording with /clock: a use_sim_time node runs
    on the recorded /clock (100 s to 199 s), not on the receive times (2023) nor its wall clock."""
    path = make_bag(tmp_path / "run.mcap", count=100, period_ns=10_000_000, with_clock=True)
    listener = await start_node(lambda s: Listener(s, {"/points": PointStamped, "/clock": Time}, use_sim_time=True))
    status, out, err = await skydeck(
        core.url, "bag", "play", str(path), "--clock", "--topics", "/points", "--wait-for-subscribers", timeout_s=60
    )
    assert status == 0, err
    assert "played 200 messages" in out, out  # /points and the recorded /clock
    await wait_until(lambda: len(frames(listener, "/points")) == 100, what="every /points message")
    await wait_until(lambda: listener.get_clock().now().nanoseconds == 199 * 10**9, what="the last recorded /clock")
    assert frames(listener, "/points") == [point_frame(i) for i in range(100)]
    ticks = [Time.model_validate_json(frame).sec for frame in frames(listener, "/clock")]
    assert ticks and ticks == list(range(200 - len(ticks), 200))  # in order from when the listener linked


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["bag", "info", "{tmp}/missing.mcap"], "no such file"),
        (["bag", "info", "{tmp}/text.mcap"], "not an MCAP recording"),
        (["bag", "info", "{tmp}"], "is a folder"),
        (["bag", "info", "{tmp}/cut.mcap"], "holds no complete chunk"),
        (["bag", "play", "{tmp}/cut.mcap"], "holds no complete chunk"),
        (["bag", "play", "{tmp}/run.mcap", "--topics", "/nope"], "has no topic /nope"),
        (["bag", "play", "{tmp}/run.mcap", "--remap", "/points"], "--remap takes FROM:=TO"),
        (["bag", "play", "{tmp}/run.mcap", "--remap", "/nope:=/x"], "--remap names /nope"),
        (["bag", "play", "{tmp}/run.mcap", "--start-offset", "99"], "past the end"),
        (["bag", "play", "{tmp}/run.mcap", "--topics", "bad//name"], "invalid"),
        (["bag", "record"], "name the topics to record, or -a"),
        (["bag", "record", "-a", "/points"], "not both"),
        (["bag", "record", "-a", "-x", "("], "not a regular expression"),
        (["bag", "record", "-a", "-o", "{tmp}/run.mcap"], "already exists"),
        (["bag", "record", "-a", "-o", "{tmp}/no/such/dir/x"], "does not exist"),
        (["bag", "record", "-a", "-o", "{tmp}/text.mcap/x"], "cannot write"),
    ],
)
async def test_bad_input_is_one_clear_line_and_a_non_zero_status(
    core, tmp_path: Path, monkeypatch, capsys, args: list[str], says: str
) -> None:
    """In-process through ``main`` (what the `skydeck` script runs): quick, so every case is here."""
    from services.cli.main import main

    make_bag(tmp_path / "run.mcap")
    (tmp_path / "text.mcap").write_text("not a recording")
    (tmp_path / "cut.mcap").write_bytes((tmp_path / "run.mcap").read_bytes()[:50])
    monkeypatch.setenv("SKYDECK_CORE_URL", core.url)
    status = await asyncio.to_thread(main, [arg.format(tmp=tmp_path) for arg in args])
    err = capsys.readouterr().err
    assert status == 1 and err.startswith("skydeck: error:") and says in err and err.count("\n") == 1, err


async def test_a_bad_flag_value_is_argparse_s_one_line_and_status_2(core) -> None:
    status, _, err = await skydeck(core.url, "bag", "play", "x.mcap", "--rate", "0")
    assert status == 2 and "expected a positive number" in err.splitlines()[-1]


async def test_play_refuses_a_topic_of_another_type_in_the_running_system(core, start_node, tmp_path: Path) -> None:
    from services.runtime import Node
    from shared_models.std_msgs import String

    class Clash(Node):
        def __init__(self, settings) -> None:
            super().__init__("clash", settings=settings)
            self.create_publisher(String, "/points", 10)

    await start_node(Clash)
    status, _, err = await skydeck(core.url, "bag", "play", str(make_bag(tmp_path / "run.mcap")))
    assert status == 1 and "/points is std_msgs/msg/String in the running system" in err and err.count("\n") == 1


async def test_record_and_play_without_a_core_are_one_line(tmp_path: Path) -> None:
    url = f"http://127.0.0.1:{free_port()}"
    status, _, err = await skydeck(url, "bag", "record", "-a", "-o", str(tmp_path / "x"))
    assert status == 1 and "cannot reach the core" in err and not (tmp_path / "x.mcap").exists()
    status, _, err = await skydeck(url, "bag", "play", str(make_bag(tmp_path / "run.mcap")))
    assert status == 1 and "cannot reach the core" in err


async def test_space_pauses_and_resumes_in_a_terminal(core, tmp_path: Path) -> None:
    """`bag play` in a real pseudo-terminal: a space typed pauses it, another resumes it."""
    import pty

    path = make_bag(tmp_path / "run.mcap", count=100, period_ns=20_000_000)  # 2 s
    leader, follower = pty.openpty()
    env = {**os.environ, "SKYDECK_CORE_URL": core.url, "PYTHONUNBUFFERED": "1"}
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "bag", "play", str(path),
        stdin=follower, stdout=follower, stderr=follower, env=env,
    )  # fmt: skip
    os.close(follower)
    output = bytearray()

    async def read_until(text: bytes, timeout_s: float = 20.0) -> None:
        async with asyncio.timeout(timeout_s):
            while text not in output:
                chunk = await asyncio.to_thread(os.read, leader, 1024)
                output.extend(chunk)

    try:
        await read_until(b"playing")
        os.write(leader, b" ")
        await read_until(b"[PAUSED]")
        os.write(leader, b" ")
        await read_until(b"[RUNNING]")
        await read_until(b"played 101 messages")
        async with asyncio.timeout(20):
            assert await process.wait() == 0
    finally:
        if process.returncode is None:
            process.kill()
            await process.wait()
        os.close(leader)
    assert b"Traceback" not in output
