"""What a new user is told: `make install`'s last line and `skydeck launch`'s pages and command
to try, each followed as printed in a new terminal (a clean environment, PATH without the venv)."""

from __future__ import annotations

import asyncio
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from services.launch.background import BackgroundProcess
from services.launch.next_steps import TRY_COMMAND, next_steps, shell_prefix
from tests.conftest import free_port_block

REPO = Path(__file__).resolve().parents[3]
VENV = Path(sys.prefix)
# What a new terminal has: the system's PATH, a home, and none of this session's venv.
NEW_TERMINAL = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": os.environ.get("HOME", "/tmp"), "LANG": "C.UTF-8"}

pytestmark = pytest.mark.skipif(sys.prefix == sys.base_prefix, reason="the tests run in the project's venv")


def _in_new_terminal(command: str, **env: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ["bash", "--noprofile", "--norc", "-c", command], env={**NEW_TERMINAL, **env}, cwd="/",
        capture_output=True, text=True, timeout=30,
    )  # fmt: skip


def _planned(target: str) -> subprocess.CompletedProcess[str]:
    """What `make -n TARGET` would run, as a user's shell runs it (not inside `make test`'s make)."""
    outside_make = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MAKELEVEL", "MFLAGS", "MAKEOVERRIDES")}
    return subprocess.run(
        ["make", "--no-print-directory", "-n", target], cwd=REPO, env=outside_make,
        capture_output=True, text=True, timeout=30, check=True,
    )  # fmt: skip


def test_make_install_ends_with_how_a_new_terminal_finds_skydeck() -> None:
    planned = _planned("install")
    last = planned.stdout.strip().splitlines()[-1]
    activate = REPO / ".venv" / "bin" / "activate"
    assert last.startswith("echo ") and f"source {activate}" in last, last
    printed = _in_new_terminal(last).stdout.strip()  # the line as make prints it
    assert printed.endswith(f"in each new terminal, first: source {activate}"), printed
    assert _in_new_terminal("command -v skydeck").returncode != 0  # the premise: not on PATH yet
    found = _in_new_terminal(f"source {activate} && skydeck --help")
    assert found.returncode == 0 and "usage: skydeck" in found.stdout, found.stderr


def test_make_up_and_make_robot_launch_without_the_install_line() -> None:
    for target, command in (("up", ".venv/bin/skydeck launch start_mission:="), ("robot", ".venv/bin/skydeck launch robot")):
        planned = _planned(target)
        lines = planned.stdout.strip().splitlines()
        assert lines[-1].startswith(command) and not any(line.startswith("echo") for line in lines), lines


def test_the_pages_and_the_command_name_the_core_and_how_to_reach_it() -> None:
    venv_bin = str(VENV / "bin")
    steps = next_steps("http://127.0.0.1:8000", environ={"PATH": "/usr/bin"})
    assert steps[0] == "open http://127.0.0.1:8000/ (the dashboard) and http://127.0.0.1:8000/docs (every command)"
    assert steps[1] == f"try, in another terminal: source {VENV.absolute()}/bin/activate && {TRY_COMMAND}"
    other = next_steps("http://127.0.0.1:19340/", environ={"PATH": f"/usr/bin:{venv_bin}"})
    assert other[1] == f"try, in another terminal: SKYDECK_CORE_URL=http://127.0.0.1:19340 {TRY_COMMAND}"
    # an activated venv lasts only in its terminal: the next one needs the activation again
    activated = {"PATH": f"{venv_bin}:/usr/bin", "VIRTUAL_ENV": str(VENV)}
    assert shell_prefix(environ=activated) == f"source {VENV.absolute()}/bin/activate && "


def test_outside_a_venv_or_with_its_bin_on_path_for_good_the_command_is_bare(tmp_path: Path) -> None:
    image = tmp_path / "opt" / "skydeck"  # a container's venv, its bin on PATH by the image's ENV
    (image / "bin").mkdir(parents=True)
    assert shell_prefix(environ={"PATH": f"{image}/bin:/usr/bin"}, venv=image) == ""
    assert shell_prefix(environ={"PATH": "/usr/bin"}, venv=image) == f"source {image}/bin/activate && "


@pytest.mark.e2e
@pytest.mark.timeout(90)
async def test_launch_prints_what_to_open_and_a_command_that_works_in_a_new_terminal() -> None:
    base = free_port_block(2)
    launch = BackgroundProcess(
        [VENV / "bin" / "skydeck", "launch", "robot", "--base-port", str(base), "--seed", "1",
         "--rosbridge-port", "0", "--foxglove-port", "0"],
        name="launch", cwd=REPO, env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    try:
        await launch.await_line("[launch] try, in another terminal: ", 60)
        url = f"http://127.0.0.1:{base}"
        assert f"[launch] open {url}/ (the dashboard) and {url}/docs (every command)" in launch.lines
        command = next(line for line in launch.lines if "try, in another" in line).partition(": ")[2]
        listed = await asyncio.to_thread(_in_new_terminal, command)
        assert listed.returncode == 0, listed.stderr
        assert "/scan" in listed.stdout.split() and "/cmd_vel" in listed.stdout.split(), listed.stdout
        # started with the core, the simulator waited for it without a word
        assert not [line for line in launch.lines if "waiting for core" in line], launch.tail()
    finally:
        assert await asyncio.to_thread(launch.stop, signal.SIGINT, 30)
