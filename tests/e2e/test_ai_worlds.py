"""The AI's saved progress belongs to one build of a world (issue 21), on real processes: a rerun
of the same seed flies again, a restarted AI resumes without a second visit and leaves a finished
world finished, a reset starts a new tour over the new boxes, and a damaged state file is
ignored with a warning."""

from __future__ import annotations

import asyncio
import json
import math
import os
import re
import signal
import sys

import httpx
import pytest

from services.ai.progress import FILE_NAME
from tests.e2e.conftest import LaunchedSystem
from tests.e2e.mission import ai_process, box_positions, recording, stop_launch

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(240)]

VISITED_M = 0.3 + 0.05  # the AI's visit radius, and a little for the pose rate


async def _world_id(system: LaunchedSystem) -> str:
    async with httpx.AsyncClient() as http:
        reply = await http.get(system.core_url + "/simulator/world", timeout=5)
    reply.raise_for_status()
    return str(reply.json()["id"])


async def _done(system: LaunchedSystem, timeout_s: float = 120) -> dict:
    return await system.messages("/ai/status", lambda m: m["state"] in ("done", "error"), timeout_s)


async def _ai_pid(system: LaunchedSystem) -> int:
    return next(n["pid"] for n in (await system.graph())["nodes"] if n["name"] == "/ai")


def _fly_commands(lines: list[str]) -> list[tuple[float, float]]:
    """The targets control accepted, from its log ("Flying to (x, y)")."""
    found = (re.search(r"\[control\].*Flying to \(([-\d.e+]+), ([-\d.e+]+)\)", line) for line in lines)
    return [(float(m.group(1)), float(m.group(2))) for m in found if m]


async def test_two_launches_of_the_same_seed_with_one_state_folder_both_fly_over_every_box(launch, tmp_path) -> None:
    state = tmp_path / "state"
    worlds = []
    for run in range(2):
        system = await launch("--speed", "max", "--seed", "7", "--boxes", "3", "--exclude", "ai")
        boxes = await box_positions(system, 3)
        async with recording(system, boxes) as track, ai_process(system, state) as ai:
            status = await _done(system)
            await asyncio.wait_for(_landed(track), 20)
        assert status["state"] == "done", (run, status, ai.lines[-20:])
        assert sorted(status["visited"]) == [0, 1, 2]
        assert max(track.closest) <= VISITED_M, (run, track.closest)  # physically over every box
        world = await _world_id(system)
        assert any(f"new world {world}: 3 boxes" in line for line in ai.lines), ai.lines
        worlds.append(world)
        await stop_launch(system)
    assert worlds[0] != worlds[1]  # the same seed, built twice: two worlds
    saved = json.loads((state / FILE_NAME).read_text())["worlds"]
    assert [(w["world"], w["done"]) for w in saved] == [(worlds[0], True), (worlds[1], True)]


async def _landed(track) -> None:  # type: ignore[no-untyped-def]
    while not track.landed:
        await asyncio.sleep(0.05)


async def test_ai_killed_mid_mission_comes_back_and_finishes_without_a_second_visit(launch) -> None:
    system = await launch("--speed", "10", "--seed", "5", "--boxes", "6", "start_mission:=true")
    boxes = await box_positions(system, 6)
    pid = await _ai_pid(system)
    await system.messages("/ai/status", lambda m: len(m["visited"]) >= 2, 120)
    os.kill(pid, signal.SIGKILL)
    mark = len(system.lines)
    await system.wait_for_line("[launch] ai exited", timeout_s=20)
    await system.wait_for_line("[launch] ai ready", timeout_s=30, after=mark)
    status = await _done(system)
    assert status["state"] == "done", status
    assert sorted(status["visited"]) == list(range(6)) and len(status["visited"]) == 6
    world = await _world_id(system)
    resumed = [line for line in system.lines if f"resuming world {world}:" in line]
    assert resumed and re.search(r": [2-5] of 6 visited", resumed[0]), resumed
    # No second visit: control was sent to each box exactly once, across the AI's restart (the
    # restarted AI's command to the box it was flying to is refused as the same target).
    commands = _fly_commands(system.lines)
    # (Near the box, not at it: perception's first reading can be of a box still settling, and
    # the AI aims at where it saw the box last; boxes stand metres apart.)
    for box in boxes:
        assert sum(math.dist(box, target) < 0.5 for target in commands) == 1, (box, commands)

    # A finished world stays finished: the AI restarted after "done" does not fly it again.
    take_offs = sum("Handling take off!" in line for line in system.lines)
    pid = await _ai_pid(system)
    os.kill(pid, signal.SIGKILL)
    mark = len(system.lines)
    await system.wait_for_line("[launch] ai ready", timeout_s=30, after=mark)
    await system.wait_for_line(f"resuming world {world}: 6 of 6 visited", timeout_s=20, after=mark)
    status = await system.messages("/ai/status", lambda m: m["state"] == "done" and "is done" in m["message"], 20)
    assert sorted(status["visited"]) == list(range(6))
    assert sum("Handling take off!" in line for line in system.lines) == take_offs
    pose = await system.messages("/drone/pose", lambda m: True, 10)
    assert pose["pose"]["position"]["z"] <= 0.1


async def test_a_reset_mid_mission_starts_a_new_tour_over_the_new_boxes(launch, tmp_path) -> None:
    system = await launch("--speed", "10", "--seed", "9", "--boxes", "4", "start_mission:=true")
    old_boxes = await box_positions(system, 4)
    old_world = await _world_id(system)
    pid = await _ai_pid(system)
    await system.messages("/ai/status", lambda m: len(m["visited"]) >= 1, 120)
    # The AI is held while the terminal's command starts (seconds on a loaded machine, in which
    # a 10x tour could finish), so the reset lands mid-tour however slow the machine.
    os.kill(pid, signal.SIGSTOP)
    mark = len(system.lines)
    try:
        # The way a user resets from a terminal (the dashboard's button calls the same service).
        reset = await asyncio.create_subprocess_exec(
            sys.executable, "-m", "services.cli", "service", "call", "/simulator/reset",
            env={**os.environ, "SKYDECK_CORE_URL": system.core_url},
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
        )  # fmt: skip
        output, _ = await asyncio.wait_for(reset.communicate(), 30)
    finally:
        os.kill(pid, signal.SIGCONT)
    assert reset.returncode == 0, output
    new_world = await _world_id(system)
    assert new_world != old_world and new_world in output.decode()
    await system.wait_for_line(f"new world {new_world}: 4 boxes", timeout_s=30, after=mark)
    new_boxes = await box_positions(system, 4)
    async with recording(system, new_boxes) as track:
        status = await _done(system)
        await asyncio.wait_for(_landed(track), 20)
    assert status["state"] == "done", status
    assert sorted(status["visited"]) == [0, 1, 2, 3]
    assert all(math.dist(a, b) > 1.0 for a, b in zip(old_boxes, new_boxes, strict=True))
    assert max(track.closest) <= VISITED_M, track.closest  # the new tour flew over the new boxes
    saved = {w["world"]: w for w in json.loads((tmp_path / "state" / FILE_NAME).read_text())["worlds"]}
    assert not saved[old_world]["done"] and 1 <= len(saved[old_world]["visited"]) < 4
    assert saved[new_world]["done"] and sorted(saved[new_world]["visited"]) == [0, 1, 2, 3]


@pytest.mark.parametrize("damage", ["corrupt", "unreadable"])
async def test_a_corrupt_or_unreadable_state_file_is_ignored_with_a_warning(launch, tmp_path, damage) -> None:
    state_file = tmp_path / "state" / FILE_NAME
    state_file.parent.mkdir()
    if damage == "corrupt":
        state_file.write_bytes(b'{"version": 2, "worlds": [{"world": \xff')
    else:
        state_file.mkdir()  # a directory where the file should be: reading and replacing it fail
    system = await launch("--speed", "max", "--seed", "3", "--boxes", "2", "start_mission:=true")
    status = await _done(system)
    assert status["state"] == "done" and sorted(status["visited"]) == [0, 1], status
    warnings = [line for line in system.lines if "[ai]" in line and "progress" in line and "WARN" in line]
    assert any("ignoring the AI's progress file" in line for line in warnings), system.lines
    if damage == "corrupt":  # replaced by the next save
        saved = json.loads(state_file.read_text())["worlds"]
        assert [(w["world"], w["done"]) for w in saved] == [(await _world_id(system), True)]
    else:  # cannot be replaced: said once, and the mission went on
        assert sum("cannot save the AI's progress" in line for line in warnings) == 1, warnings
