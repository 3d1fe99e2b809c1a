"""Two robots (`--robots 2`), a behaviour on each, by namespace: neither hears the other's; and
the keyboard teleop, in a pseudo-terminal, drives its robot and gives the terminal back."""

from __future__ import annotations

import math
import os
import pty
import signal
import subprocess
import sys
import termios
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

from sim_server.robot.limits import ROBOT_STARTS_M
from tests.sim_server.robot.room import Recorder, behaviour, reset_room, start_room, truth, wait_for
from tests.web_ui.system import REPO, System

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "3", "--speed", "4", "--robots", "2")
    yield system
    system.stop()


@pytest.fixture
def moved_room(room: System) -> Iterator[System]:
    """The room for a test that drives both robots away: reset after it, for the next."""
    yield room
    reset_room(room)


def _moved(system: System, robot: int) -> float:
    x, y, _ = truth(system, robot)
    sx, sy = ROBOT_STARTS_M[robot]
    return math.hypot(x - sx, y - sy)


def _printed(lines: list[str], text: str, timeout_s: float) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if any(text in line for line in lines):
            return True
        time.sleep(0.02)
    return False


def test_a_behaviour_in_one_namespace_leaves_the_other_robot_alone(room: System) -> None:
    with Recorder(room, "/robot1/cmd_vel") as robot1_commands, behaviour(room, "estop", "--namespace", "/robot2") as node:
        node.wait_for_line("the way ahead is clear: driving", 30)
        wait_for(room, "/robot2/odom", lambda m: m["pose"]["pose"]["position"]["x"] > 0.5, timeout_s=30)
    assert robot1_commands.messages == []
    assert _moved(room, 0) < 0.01 and _moved(room, 1) > 0.5
    assert "/robot2/cmd_vel" in {t["name"] for t in wait_for(room, "/api/graph", lambda g: True)["topics"]}


@pytest.mark.parametrize(
    "form", [("--namespace", "/robot{n}"), ("--ros-args", "-r", "__ns:=/robot{n}")], ids=["--namespace", "__ns"]
)
def test_one_behaviour_per_robot_each_a_node_in_its_namespace(moved_room: System, form: tuple[str, ...]) -> None:
    room = moved_room
    def where_for(n: int) -> list[str]:
        return [word.format(n=n) for word in form]

    starts = [truth(room, robot)[:2] for robot in (0, 1)]
    with behaviour(room, "wall_follower", *where_for(1)) as first, behaviour(room, "wall_follower", *where_for(2)) as second:
        wait_for(room, "/api/graph", lambda g: {"/robot1/wall_follower", "/robot2/wall_follower"} <= {n["name"] for n in g["nodes"]})
        for robot in (0, 1):  # both drive, each its own robot, at once
            wait_for(room, "/simulator/robots", lambda m, r=robot: _distance(m, r, starts[r]) > 0.3, timeout_s=30)
        graph = wait_for(room, "/api/graph", lambda g: True)
        publishers = {t["name"]: t["publishers"] for t in graph["topics"]}
        assert publishers["/robot1/cmd_vel"] == ["/robot1/wall_follower"]
        assert publishers["/robot2/cmd_vel"] == ["/robot2/wall_follower"]
        assert "/wall_follower" not in {n["name"] for n in graph["nodes"]}
        assert first.returncode is None and second.returncode is None  # neither took the other's name


def _distance(robots: dict[str, Any], robot: int, start: tuple[float, float]) -> float:
    position = robots["poses"][robot]["position"]
    return math.hypot(position["x"] - start[0], position["y"] - start[1])


def test_a_bad_parameter_or_namespace_is_one_line() -> None:
    for args, expected in (
        (["estop", "--ros-args", "-p", "distance:=near"], "parameter 'distance' is of type double; got string 'near'"),
        (["wall_follower", "--ros-args", "-p", "side:=up"], "side must be 'left' or 'right'"),
        (["estop", "--namespace", "robot 1"], "invalid name"),
    ):
        done = subprocess.run(
            [sys.executable, "-m", "services.cli", "run", *args], cwd=REPO, capture_output=True, text=True, timeout=30,
            env={**os.environ, "SKYDECK_CORE_URL": "http://127.0.0.1:9"},
        )  # fmt: skip
        assert done.returncode != 0, args
        assert expected in done.stderr and "Traceback" not in done.stderr, done.stderr


def test_teleop_drives_from_the_keyboard_and_restores_the_terminal(room: System) -> None:
    leader, follower = pty.openpty()
    before = termios.tcgetattr(follower)
    process = subprocess.Popen(
        [sys.executable, "-m", "services.cli", "run", "teleop", "--use-sim-time", "--namespace", "/robot1"],
        cwd=REPO, stdin=follower, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
        env={**os.environ, "SKYDECK_CORE_URL": room.url, "PYTHONUNBUFFERED": "1"}, start_new_session=True,
    )  # fmt: skip
    lines: list[str] = []
    ready = threading.Event()

    def read() -> None:
        for line in process.stdout:  # type: ignore[union-attr]
            lines.append(line)
            if "CTRL-C to quit" in line:
                ready.set()

    threading.Thread(target=read, daemon=True).start()
    try:
        assert ready.wait(30), "".join(lines)
        assert "publishing to /robot1/cmd_vel" in "".join(lines)
        assert not termios.tcgetattr(follower)[3] & termios.ICANON  # cbreak: key by key
        start = _moved(room, 0)
        os.write(leader, b"i")  # forward
        wait_for(room, "/robot1/odom", lambda m: m["twist"]["twist"]["linear"]["x"] > 0.15, timeout_s=20)
        wait_for(room, "/robot1/odom", lambda m: m["pose"]["pose"]["position"]["x"] > 0.4, timeout_s=20)
        os.write(leader, b"k")  # stop
        wait_for(room, "/robot1/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3, timeout_s=20)
        assert _moved(room, 0) > start + 0.4
        os.write(leader, b"q")  # 10% faster: it says so
        assert _printed(lines, "speed 0.22\tturn 1.10", 10), "".join(lines)
    finally:
        process.send_signal(signal.SIGINT)
        code = process.wait(15)
    assert code == 0, "".join(lines)
    assert termios.tcgetattr(follower) == before  # the terminal as it was
    assert "Traceback" not in "".join(lines)
    os.close(leader)
    os.close(follower)


def test_teleop_without_a_terminal_says_so() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "run", "teleop"], cwd=REPO, capture_output=True, text=True,
        stdin=subprocess.DEVNULL, timeout=30, env={**os.environ, "SKYDECK_CORE_URL": "http://127.0.0.1:9"},
    )  # fmt: skip
    assert done.returncode != 0
    assert "standard input is not one" in done.stderr and "Traceback" not in done.stderr
