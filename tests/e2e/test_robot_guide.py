"""docs/robot.md cannot rot: its Python is the shipped file, its commands run in order.

`skydeck launch` lines start the system (a later one replaces the earlier); a `skydeck run` line
stops the previous `run` (Ctrl-C, as the tutorial says to) and starts the node, which must then
do what the tutorial says it does (its log line below); `teleop` runs in a pseudo-terminal and is
driven with its keys. Every other `skydeck` line must exit 0 without a traceback. The changes
made to the tutorial's commands: `launch` runs the simulation at 8x real time and nodes get
`--use-sim-time`, to keep the test short.
"""

from __future__ import annotations

import asyncio
import os
import pty
import shlex
import signal
import subprocess
import sys
import termios
from pathlib import Path

import pytest

from services.launch.background import BackgroundProcess
from tests.e2e.conftest import stop_launch
from tests.e2e.guide import code_blocks, skydeck_commands

pytestmark = [pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(600)]

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "robot.md"
# What each node of the tutorial prints once it has done what the tutorial says.
_DONE = {
    "examples/robot/my_estop.py": "stopped: the wall is",
    "drive_square": "square done",
    "estop": "ahead: stopped",
    "wall_follower": "following",
    "person_follower": "following",
    "obstacle_avoider": "reached",
    "fsm": "state follow_wall",
    "examples/robot/ball_tracker.py": "ball in sight",
}


def test_python_in_the_guide_is_the_shipped_file() -> None:
    (block,) = code_blocks(GUIDE, "python")
    assert block == (ROOT / "examples" / "robot" / "my_estop.py").read_text()


def test_every_node_of_the_guide_is_checked() -> None:
    runs = {args[1] for args in skydeck_commands(GUIDE) if args[0] == "run"}
    assert runs == {*_DONE, "teleop"}


class _Terminal:
    """`skydeck run teleop` in a pseudo-terminal, as a user at a keyboard runs it."""

    def __init__(self, args: list[str], env: dict[str, str]) -> None:
        self.leader, follower = pty.openpty()
        self.follower = follower
        self.before = termios.tcgetattr(follower)
        self.process = subprocess.Popen(
            [sys.executable, "-m", "services.cli", *args], cwd=ROOT, env=env, stdin=follower,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True,
        )  # fmt: skip

    def stop(self) -> None:
        self.process.send_signal(signal.SIGINT)
        output, _ = self.process.communicate(timeout=15)
        assert self.process.returncode == 0 and "Traceback" not in output, output
        assert termios.tcgetattr(self.follower) == self.before, "teleop left the terminal changed"
        os.close(self.leader)
        os.close(self.follower)


async def test_every_command_in_the_guide_runs(launch) -> None:
    system = None
    node: BackgroundProcess | _Terminal | None = None
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}

    def stop_node() -> None:
        if node is not None:
            node.stop() if isinstance(node, _Terminal) else _stop(node)

    try:
        for args in skydeck_commands(GUIDE):
            if args[0] == "launch":
                stop_node()
                node = None
                if system is not None:
                    await asyncio.to_thread(stop_launch, system.process)
                system = await launch(*args[1:], "--speed", "8")
                env["SKYDECK_CORE_URL"] = system.core_url
                continue
            assert system is not None, "the guide runs a command before starting the system"
            if args[0] == "run":
                stop_node()
                run = [args[0], args[1], "--use-sim-time", *args[2:]]
                if args[1] == "teleop":
                    node = _Terminal(run, env)
                    await _drive_with_keys(system, node)
                    continue
                node = BackgroundProcess(
                    [sys.executable, "-m", "services.cli", *run], name=f"skydeck {shlex.join(args)}", cwd=ROOT, env=env
                )
                await node.await_line(_DONE[args[1]], 180)
                continue
            process = await asyncio.create_subprocess_exec(
                sys.executable, "-m", "services.cli", *args, cwd=ROOT, env=env,
                stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
            )  # fmt: skip
            stdout, stderr = await asyncio.wait_for(process.communicate(), 60)
            assert process.returncode == 0, f"skydeck {shlex.join(args)}: {stderr.decode()}"
            assert b"Traceback" not in stderr
            if args[:3] == ["topic", "echo", "/fsm/state"]:
                assert b"data: follow_wall" in stdout, stdout.decode()
    finally:
        stop_node()


def _stop(process: BackgroundProcess) -> None:
    process.stop(signal.SIGINT, timeout_s=10)
    assert process.returncode == 0 and not any("Traceback" in line for line in process.lines), process.tail()


async def _drive_with_keys(system, terminal: _Terminal) -> None:  # type: ignore[no-untyped-def]
    """Wait for teleop's help, press `i` (forward) until /odom moves, then `k` (stop)."""
    assert terminal.process.stdout is not None
    async with asyncio.timeout(30):
        while "CTRL-C to quit" not in await asyncio.to_thread(terminal.process.stdout.readline):
            pass
    os.write(terminal.leader, b"i")
    await system.messages("/odom", lambda m: m["pose"]["pose"]["position"]["x"] > 0.2, 30)
    os.write(terminal.leader, b"k")
    await system.messages("/odom", lambda m: abs(m["twist"]["twist"]["linear"]["x"]) < 1e-3, 30)
