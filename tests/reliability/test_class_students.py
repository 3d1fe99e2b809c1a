"""Students of a class as they work: their programs run unchanged from `skydeck run` with their
token (the namespace comes from it, another's is refused in one line), and one student's
flooding cannot disturb another's robot or the world's clock (the flooding connection is shed
with 4002, a flooding node's frames are the subscriber's bounded queue's).

Each test asserts delivery and continuity, never timings: rates are `skydeck bench`'s.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import struct
import sys
import textwrap
from collections.abc import AsyncIterator
from pathlib import Path

import pytest
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosed

from services.access import make_class_tokens, write_tokens
from services.runtime import Node
from services.runtime.edge.links import stream_url
from shared_models.geometry_msgs import Twist, Vector3
from shared_models.std_srvs import Trigger
from tests.conftest import wait_until
from tests.reliability.classroom import WALL_FOLLOWER, Classroom, open_classroom

pytestmark = pytest.mark.timeout(90)

REPO = Path(__file__).resolve().parents[2]



@pytest.fixture
async def room(tmp_path: Path) -> AsyncIterator[Classroom]:
    async for running in open_classroom(tmp_path, student_messages_per_s=100.0):
        yield running


async def _skydeck_run(room: Classroom, student: str, program: Path, *argv: str) -> asyncio.subprocess.Process:
    """`skydeck run PROGRAM` as the student runs it on their own machine: the core's URL and
    their token in the environment, nothing else."""
    env = {**os.environ, "SKYDECK_CORE_URL": room.url, "SKYDECK_TOKEN": room.token(student), "PYTHONUNBUFFERED": "1"}
    return await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "run", str(program), *argv,
        cwd=REPO, env=env, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
    )  # fmt: skip


@contextlib.asynccontextmanager
async def _running(process: asyncio.subprocess.Process) -> AsyncIterator[asyncio.subprocess.Process]:
    try:
        yield process
    finally:
        if process.returncode is None:
            process.terminate()
            await asyncio.wait_for(process.wait(), 20)


async def test_a_students_program_runs_unchanged_in_their_namespace(room: Classroom, tmp_path: Path) -> None:
    program = tmp_path / "wall_follower.py"
    program.write_text(WALL_FOLLOWER.format(topic="cmd_vel"))
    async with _running(await _skydeck_run(room, "alice", program)):
        await wait_until(lambda: any(c.linear.x == 0.3 for c in room.world.commands["alice"]), 30, "alice's robot to move")
        assert "/alice/wall_follower" in room.core.registry.nodes
    assert room.world.commands["bob"] == []


async def test_her_own_namespace_given_by_hand_is_taken(room: Classroom, tmp_path: Path) -> None:
    program = tmp_path / "wall_follower.py"
    program.write_text(WALL_FOLLOWER.format(topic="cmd_vel"))
    async with _running(await _skydeck_run(room, "alice", program, "--ros-args", "-r", "__ns:=/alice")):
        await wait_until(lambda: "/alice/wall_follower" in room.core.registry.nodes, 30, "the node")


@pytest.mark.parametrize(
    "argv", [["--ros-args", "-r", "__ns:=/bob"], ["__ns:=/bob"]], ids=["ros2-remap", "ros1-remap"]
)
async def test_another_students_namespace_is_refused_in_one_line(room: Classroom, tmp_path: Path, argv: list[str]) -> None:
    program = tmp_path / "wall_follower.py"
    program.write_text(WALL_FOLLOWER.format(topic="cmd_vel"))
    process = await _skydeck_run(room, "alice", program, *argv)
    out, _ = await asyncio.wait_for(process.communicate(), 30)
    assert process.returncode == 1
    lines = out.decode().strip().splitlines()
    assert lines == ["skydeck: error: your token is alice's: your nodes run in /alice, not /bob (leave the namespace out, or give /alice)"]
    assert room.world.commands["bob"] == []


async def test_a_behaviours_namespace_flag_is_checked_too(room: Classroom) -> None:
    env = {**os.environ, "SKYDECK_CORE_URL": room.url, "SKYDECK_TOKEN": room.token("alice")}
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "run", "estop", "--namespace", "/bob",
        cwd=REPO, env=env, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
    )  # fmt: skip
    out, _ = await asyncio.wait_for(process.communicate(), 30)
    assert process.returncode == 1 and out.decode().startswith("skydeck: error: your token is alice's")


async def test_a_node_reaching_out_of_its_namespace_is_refused_by_the_core_in_one_line(room: Classroom, tmp_path: Path) -> None:
    program = tmp_path / "wall_follower.py"
    program.write_text(WALL_FOLLOWER.format(topic="/bob/cmd_vel"))  # an absolute name: bob's robot
    async with _running(await _skydeck_run(room, "alice", program)) as process:
        assert process.stdout is not None
        refused = ""
        async with asyncio.timeout(30):
            while "refused" not in refused:
                refused = (await process.stdout.readline()).decode()
                assert refused, "the program ended without saying why"
    assert "the core refused /alice/wall_follower: alice may not publish on /bob/cmd_vel: only under /alice" in refused
    assert room.world.commands["bob"] == []


# -- isolation ----------------------------------------------------------------------------------


class Steady:
    """bob driving his robot through the core at a steady pace, each command numbered, and a
    reader of the world's /clock through the core: what must go on whatever alice does."""

    def __init__(self, room: Classroom) -> None:
        self.room = room
        self.sent = 0
        self.clock: list[int] = []

    async def drive(self, stop: asyncio.Event) -> None:
        url = stream_url(self.room.url, "/bob/cmd_vel", mode="publish", type="geometry_msgs/msg/Twist", token=self.room.token("bob"))
        async with connect(url) as ws:
            # As in ROS, what is published before the subscriber has linked is not delivered to
            # it: stand still until the world hears bob, then number every command.
            while not self.room.world.commands["bob"]:
                await ws.send(Twist().model_dump_json())
                await asyncio.sleep(0.02)
            while not stop.is_set():
                self.sent += 1
                await ws.send(Twist(linear=Vector3(x=float(self.sent))).model_dump_json())
                await asyncio.sleep(0.02)

    @property
    def received(self) -> list[float]:
        return [c.linear.x for c in self.room.world.commands["bob"] if c.linear.x > 0]

    async def read_clock(self, stop: asyncio.Event) -> None:
        async with connect(stream_url(self.room.url, "/clock", mode="subscribe", token=self.room.token("bob"))) as ws:
            while not stop.is_set():
                with contextlib.suppress(TimeoutError):
                    stamp = json.loads(await asyncio.wait_for(ws.recv(), 0.5))
                    self.clock.append(stamp["sec"] * 50 + stamp["nanosec"] // 20_000_000)

    def check(self) -> None:
        assert self.received == [float(n) for n in range(1, self.sent + 1)]  # all, in order
        assert len(self.clock) > 20 and self.clock == list(range(self.clock[0], self.clock[0] + len(self.clock)))


@contextlib.asynccontextmanager
async def _steady(room: Classroom) -> AsyncIterator[Steady]:
    steady = Steady(room)
    stop = asyncio.Event()
    tasks = [asyncio.create_task(steady.drive(stop)), asyncio.create_task(steady.read_clock(stop))]
    try:
        await wait_until(lambda: len(steady.received) > 5 and len(steady.clock) > 5, 20, "bob and the clock")
        yield steady
        await wait_until(lambda: len(steady.clock) > 20, 20, "more of the clock")
    finally:
        stop.set()
        await asyncio.gather(*tasks)
    await wait_until(lambda: len(steady.received) >= steady.sent, 10, "bob's last commands")
    steady.check()


async def _flood_native(room: Classroom) -> tuple[int, str]:
    url = stream_url(room.url, "/alice/cmd_vel", mode="publish", type="geometry_msgs/msg/Twist", token=room.token("alice"))
    frame = Twist(linear=Vector3(x=9.0)).model_dump_json()
    async with connect(url) as ws:
        with pytest.raises(ConnectionClosed) as closed:
            while True:
                await ws.send(frame)
    assert closed.value.rcvd is not None
    return closed.value.rcvd.code, closed.value.rcvd.reason


async def _until_the_world_hears_alice(room: Classroom, ws: ClientConnection, frame: str | bytes) -> None:
    """Send ``frame`` now and then until the world has one: a flood starts once the world is
    linked. Before, what is published is not delivered (as in ROS: rosbridge's advertise is not
    latched), and a shed connection's publication ends with it, so under load the world could
    link only after the flood."""
    while not room.world.commands["alice"]:
        await ws.send(frame)
        await asyncio.sleep(0.05)


async def _flood_rosbridge(room: Classroom) -> tuple[int, str]:
    frame = json.dumps({"op": "publish", "topic": "/alice/cmd_vel", "msg": {"linear": {"x": 9.0}}})
    async with connect(f"{room.rosbridge_url}/?token={room.token('alice')}") as ws:
        await ws.send(json.dumps({"op": "advertise", "topic": "/alice/cmd_vel", "type": "geometry_msgs/msg/Twist"}))
        await _until_the_world_hears_alice(room, ws, frame)
        with pytest.raises(ConnectionClosed) as closed:
            while True:
                await ws.send(frame)
    assert closed.value.rcvd is not None
    return closed.value.rcvd.code, closed.value.rcvd.reason


async def _flood_foxglove(room: Classroom) -> tuple[int, str]:
    url = f"{room.foxglove_url}/?token={room.token('alice')}"
    channel = {"id": 7, "topic": "/alice/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/msg/Twist"}
    frame = struct.pack("<BI", 1, 7) + b'{"linear": {"x": 9.0}}'
    async with connect(url, subprotocols=["foxglove.websocket.v1"]) as ws:  # type: ignore[list-item]
        await ws.send(json.dumps({"op": "advertise", "channels": [channel]}))
        await _until_the_world_hears_alice(room, ws, frame)
        with pytest.raises(ConnectionClosed) as closed:
            while True:
                await ws.send(frame)
    assert closed.value.rcvd is not None
    return closed.value.rcvd.code, closed.value.rcvd.reason


@pytest.mark.parametrize("flood", [_flood_native, _flood_rosbridge, _flood_foxglove], ids=["native", "rosbridge", "foxglove"])
async def test_a_flooding_connection_is_shed_and_the_class_goes_on(room: Classroom, flood) -> None:  # type: ignore[no-untyped-def]
    alice_reads = await connect(stream_url(room.url, "/alice/scan", mode="subscribe", token=room.token("alice")))
    async with alice_reads, _steady(room):
        assert json.loads(await alice_reads.recv()) == {"data": "alice's scan"}
        code, reason = await flood(room)
        assert code == 4002 and reason.startswith("rate limit: alice sent over 100 messages/s")
        await alice_reads.ping()  # her other connection is still open: only the flooding one was shed
    assert room.world.commands["alice"] and all(c.linear.x == 9.0 for c in room.world.commands["alice"])


async def test_a_students_calls_waiting_at_once_are_bounded(room: Classroom, tmp_path: Path) -> None:
    class Hung(Node):
        def __init__(self) -> None:
            super().__init__("hung", namespace="/alice", settings=room.node_settings("alice"))
            self.create_service(Trigger, "/alice/hang", self._hang)

        async def _hang(self, request: object) -> None:
            await asyncio.Event().wait()

    hung = Hung()
    await hung.start()
    try:
        await wait_until(lambda: room.core.registry.service("/alice/hang") is not None, what="the hung service")
        async with room.http("alice") as alice, room.http("bob") as bob:
            waiting = [asyncio.create_task(alice.post("/alice/hang", json={}, timeout=30)) for _ in range(16)]
            await wait_until(lambda: room.core.app.state.fences.limits.bucket("alice").calls_in_flight == 16, what="16 calls")
            refused = await alice.post("/alice/ping", json={})
            assert refused.status_code == 429 and "16 service calls waiting" in refused.json()["detail"]
            assert (await bob.post("/bob/ping", json={})).json()["message"] == "bob's pong"  # bob is not alice
            for task in waiting:
                task.cancel()
            await asyncio.gather(*waiting, return_exceptions=True)
    finally:
        await hung.stop()


FLOOD_NODE = textwrap.dedent(
    """
    from services.runtime import Node, spin
    from shared_models.geometry_msgs import Twist, Vector3


    class Flood(Node):
        def __init__(self):
            super().__init__("flood")
            self.out = self.create_publisher(Twist, "cmd_vel", 10)
            self.create_timer(0.001, self.burst)

        def burst(self):
            for _ in range(200):
                self.out.publish(Twist(linear=Vector3(x=9.0)))


    spin(Flood())
    """
)


async def test_a_flooding_node_leaves_the_others_robot_and_the_clock_alone(room: Classroom, tmp_path: Path) -> None:
    """alice's node floods her cmd_vel; the world links to it directly and keeps the newest of its
    bounded queue, while bob's commands through the core all arrive, in order, and /clock goes on."""
    program = tmp_path / "flood.py"
    program.write_text(FLOOD_NODE)
    async with _running(await _skydeck_run(room, "alice", program)), _steady(room):
        await wait_until(lambda: len(room.world.commands["alice"]) > 1000, 30, "alice's flood to reach the world")


@pytest.mark.parametrize(
    ("text", "mode", "said"),
    [
        ("alice,aaaaaaaaaaaaaaaaaaaa\ninstructor,bbbbbbbbbbbbbbbbbbbb\n", 0o644, "may be read by others (mode 644)"),
        ("alice,aaaaaaaaaaaaaaaaaaaa\n", 0o600, "has no instructor line"),
    ],
)
async def test_a_core_with_a_bad_tokens_file_stops_in_one_line(tmp_path: Path, text: str, mode: int, said: str) -> None:
    tokens = tmp_path / "class-tokens.csv"
    tokens.write_text(text)
    tokens.chmod(mode)
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "core", "--port", "0", "--class-tokens", str(tokens),
        cwd=REPO, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
    )  # fmt: skip
    out, _ = await asyncio.wait_for(process.communicate(), 30)
    assert process.returncode == 1
    lines = out.decode().strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"skydeck: error: {tokens} {said}"), lines


async def test_a_core_with_class_rules_naming_a_stranger_stops_in_one_line(tmp_path: Path) -> None:
    tokens, rules = tmp_path / "class-tokens.csv", tmp_path / "class-rules.yaml"
    write_tokens(tokens, make_class_tokens(["alice", "bob"]))
    rules.write_text("reads:\n  carol: [/bob/**]\n")
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "core", "--port", "0", "--class-tokens", str(tokens), "--class-rules", str(rules),
        cwd=REPO, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
    )  # fmt: skip
    out, _ = await asyncio.wait_for(process.communicate(), 30)
    assert process.returncode == 1
    assert out.decode().strip().splitlines() == [f"skydeck: error: {rules}: reads names carol, who have no token in {tokens}"]
