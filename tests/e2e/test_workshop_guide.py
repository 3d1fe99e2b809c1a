"""docs/workshop.md cannot rot: its Python is the shipped files, its commands run in order.

`skydeck launch` and `skydeck run` lines start long-running processes (a later `launch` replaces
the earlier system); every other `skydeck` line must exit 0 without a traceback. The one change
made to the guide's commands: `launch` runs the simulation at 8x real time, to keep the test short.
"""

from __future__ import annotations

import asyncio
import os
import re
import shlex
import signal
import sys
from pathlib import Path

import pytest

from tests.e2e.guide import code_blocks, skydeck_commands

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(480)]  # a hang guard, sized for a loaded machine

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "workshop.md"


def test_python_in_the_guide_is_the_shipped_files() -> None:
    shipped = {path.read_text() for path in (ROOT / "examples" / "workshop").glob("*.py")}
    blocks = code_blocks(GUIDE, "python")
    assert len(blocks) == len(shipped) == 2
    for block in blocks:
        assert block in shipped, block.splitlines()[0]


async def test_every_command_in_the_guide_runs(launch) -> None:
    commands = skydeck_commands(GUIDE)
    assert any(c[0] == "launch" for c in commands) and any(c[0] == "run" for c in commands)
    system = None
    background: list[asyncio.subprocess.Process] = []
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    finished: asyncio.Task[dict] | None = None
    try:
        for args in commands:
            if args[0] == "launch":
                system = await launch(*args[1:], *([] if "--speed" in args else ["--speed", "8"]))
                env["SKYDECK_CORE_URL"] = system.core_url
                # Read /rosout from now on: the student's AI may finish its mission while the
                # guide's last commands still run (each a new process, slow on a loaded machine).
                finished = asyncio.create_task(system.messages("/rosout", _mission_done, 450))
                continue
            assert system is not None, "the guide runs a command before starting the system"
            if args[0] == "run":
                background.append(
                    await asyncio.create_subprocess_exec(
                        sys.executable, "-m", "services.cli", *args, cwd=ROOT, env=env,
                        stdout=asyncio.subprocess.DEVNULL, stderr=asyncio.subprocess.PIPE,
                    )
                )
                await _wait_registered(system, args[1])
                continue
            process = await asyncio.create_subprocess_exec(
                sys.executable, "-m", "services.cli", *args, cwd=ROOT, env=env,
                stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
            )
            stdout, stderr = await asyncio.wait_for(process.communicate(), 60)
            assert process.returncode == 0, f"skydeck {shlex.join(args)}: {stderr.decode()}"
            assert b"Traceback" not in stderr
        # The student's AI, run in place of the built-in one, finishes the mission.
        assert finished is not None
        await asyncio.wait_for(finished, 180)
    finally:
        if finished is not None:
            finished.cancel()
        for process in background:
            process.send_signal(signal.SIGINT)
            _, stderr = await asyncio.wait_for(process.communicate(), 15)
            assert b"Traceback" not in stderr, stderr.decode()


def _mission_done(message: dict) -> bool:
    return message["name"] == "/my_ai" and message["msg"].startswith("visited box") and "(8 of 8)" in message["msg"]


async def _wait_registered(system, path: str) -> None:
    source = (ROOT / path).read_text()
    name = "/" + re.search(r'super\(\).__init__\("([a-z_]+)"\)', source).group(1)
    async with asyncio.timeout(30):
        while name not in {n["name"] for n in (await system.graph())["nodes"]}:
            await asyncio.sleep(0.05)
