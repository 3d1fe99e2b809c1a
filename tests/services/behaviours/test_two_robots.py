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

import pytest

from sim_server.robot.limits import ROBOT_STARTS_M
from tests.sim_server.robot.room import Recorder, behaviour, start_room, truth, wait_for
from tests.web_ui.system import REPO, System

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def room() -> Iterator[System]:
    system = start_room("--seed", "3", "--speed", "4", "--robots", "2")
    yield system
    system.stop()


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
