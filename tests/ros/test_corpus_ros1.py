"""The ROS 1 corpus (tests/ros/corpus/ros1/ros_workshop: the workshop's perception, control and
AI as a student finishes them, written for real rospy) flies the mission unchanged: each file by
``skydeck run``, and the three by ``skydeck launch .../nodes.launch`` beside ``skydeck launch
--exclude perception,control,ai``. The outcome is measured from the simulator's own drone pose:
every box flown over, the drone on the ground at the end."""

from __future__ import annotations

import asyncio
import os
import signal
import sys

import httpx
import pytest

from benchmarks.mission import GroundTrack
from services.launch.background import BackgroundProcess
from tests.e2e.conftest import LaunchedSystem
from tests.e2e.mission import box_positions, recording
from tests.ros.conftest import CORPUS
from tests.web_ui.system import REPO

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(180)]

PACKAGE = CORPUS / "ros1" / "ros_workshop"
SPEED = "10"
BOXES = 3
VISITED_M = 0.5  # the AI counts a box within 0.3 m (its visit_radius); the track is sampled at 60 Hz


def _skydeck(system: LaunchedSystem, *args: str, name: str) -> BackgroundProcess:
    return BackgroundProcess(
        [sys.executable, "-m", "services.cli", *args],
        name=name,
        cwd=REPO,
        env={**os.environ, "SKYDECK_CORE_URL": system.core_url, "PYTHONUNBUFFERED": "1"},
    )


async def _mission_flown(system: LaunchedSystem, track: GroundTrack, ai: BackgroundProcess) -> None:
    """Wait for the AI to end the mission by itself, then check the drone's track."""
    assert await asyncio.to_thread(ai.popen.wait, 120) == 0, ai.tail(30)
    async with asyncio.timeout(10):
        while not track.landed:
            await asyncio.sleep(0.05)
    print(f"ROS 1 mission: closest approach to each box {[round(c, 2) for c in track.closest]} m")
    assert all(closest < VISITED_M for closest in track.closest), track.closest
    assert any("Mission complete: visited 3 boxes and landed" in line for line in ai.lines), ai.tail(20)


async def _settled_boxes(system: LaunchedSystem) -> list[tuple[float, float]]:
    """The boxes' (x, y) from the simulator once they lie still (they are dropped at the start)."""
    last: list[list[float]] = []

    def still(message: dict) -> bool:
        nonlocal last
        now = [[p["position"]["x"], p["position"]["y"], p["position"]["z"]] for p in message["poses"]]
        steady = len(now) == BOXES and len(last) == BOXES and all(
            abs(a - b) < 1e-3 for box, before in zip(now, last, strict=True) for a, b in zip(box, before, strict=True)
        )
        last = now
        return steady

    await system.messages("/simulator/boxes", still, 30)
    return [(x, y) for x, y, _ in last]


def _stopped_cleanly(process: BackgroundProcess) -> None:
    assert process.stop(signal.SIGINT, timeout_s=15), f"{process.name} did not stop on Ctrl-C"
    assert not any("Traceback" in line for line in process.lines), process.tail(30)


async def test_each_file_by_skydeck_run_flies_the_mission(launch) -> None:  # type: ignore[no-untyped-def]
    system = await launch("--speed", SPEED, "--seed", "5", "--boxes", str(BOXES), "--exclude", "perception,control,ai")
    async with httpx.AsyncClient() as http:  # `rosparam set /use_sim_time true`, as under Gazebo
        reply = await http.put(f"{system.core_url}/api/rosparam/use_sim_time", json={"value": True})
        reply.raise_for_status()
    perception = _skydeck(system, "run", str(PACKAGE / "src" / "perception.py"), name="perception.py")
    control = _skydeck(system, "run", str(PACKAGE / "src" / "control.py"), "_rate:=30", name="control.py")
    try:
        boxes = await box_positions(system, BOXES)  # from the corpus's perception
        async with recording(system, boxes) as track:
            ai = _skydeck(system, "run", str(PACKAGE / "src" / "ai.py"), name="ai.py")
            try:
                await _mission_flown(system, track, ai)
            finally:
                ai.stop(signal.SIGINT, timeout_s=10)
    finally:
        for process in (control, perception):
            await asyncio.to_thread(_stopped_cleanly, process)


async def test_nodes_launch_beside_the_simulator_flies_the_mission(launch) -> None:  # type: ignore[no-untyped-def]
    system = await launch("--speed", SPEED, "--seed", "6", "--boxes", str(BOXES), "--exclude", "perception,control,ai")
    base_port = system.core_url.rsplit(":", 1)[1]
    boxes = await _settled_boxes(system)
    async with recording(system, boxes) as track:
        nodes = _skydeck(system, "launch", "--base-port", base_port, str(PACKAGE / "launch" / "nodes.launch"), name="nodes.launch")
        try:
            await asyncio.to_thread(nodes.wait_for_line, "[launch] ai exited with exit code 0; not respawned", 150)
            async with asyncio.timeout(10):
                while not track.landed:
                    await asyncio.sleep(0.05)
        finally:
            await asyncio.to_thread(_stopped_cleanly, nodes)
    text = "\n".join(nodes.lines)
    print(f"nodes.launch mission: closest approach to each box {[round(c, 2) for c in track.closest]} m")
    assert all(closest < VISITED_M for closest in track.closest), track.closest
    assert "[launch] set 3 parameters on the core's parameter server" in text
    assert "Visiting each box within 0.30 m" in text  # <param name="visit_radius"> reached get_param("~visit_radius")
    assert "Mission complete: visited 3 boxes and landed" in text
    assert "[launch] starting perception" in text and "core :" not in text  # the running core was used
