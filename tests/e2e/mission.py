"""Watching a mission on a launched system: the AI as its own process (started after the track is
being recorded, so the whole flight is on it), and the drone's ground track from /drone/pose."""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import sys
from collections.abc import AsyncIterator
from pathlib import Path

from websockets.asyncio.client import connect

from benchmarks.mission import GroundTrack
from services.launch.background import BackgroundProcess
from services.runtime.edge.links import stream_url
from tests.e2e import conftest
from tests.e2e.conftest import LaunchedSystem

__all__ = ["ai_process", "box_positions", "recording", "stop_launch"]


def _base_port(system: LaunchedSystem) -> int:
    return int(system.core_url.rsplit(":", 1)[1])


@contextlib.asynccontextmanager
async def ai_process(system: LaunchedSystem, state_dir: Path, *args: str) -> AsyncIterator[BackgroundProcess]:
    """Run the AI beside a `skydeck launch --exclude ai`; stopped with Ctrl-C afterwards, and it
    must stop cleanly without a traceback."""
    env = {**os.environ, "SKYDECK_CORE_URL": system.core_url, "SKYDECK_STATE_DIR": str(state_dir), "PYTHONUNBUFFERED": "1"}
    ai = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "run", "ai", "--port", str(_base_port(system) + 4), "--use-sim-time", "--start-mission", *args],
        name="skydeck run ai",
        env=env,
    )
    try:
        yield ai
    finally:
        stopped = await asyncio.to_thread(ai.stop, signal.SIGINT, 20)
    assert stopped, "skydeck run ai did not stop on Ctrl-C"
    assert not any("Traceback" in line for line in ai.lines), ai.tail(40)
    assert ai.returncode == 0, ai.tail(20)


async def box_positions(system: LaunchedSystem, count: int) -> list[tuple[float, float]]:
    """Perception's boxes, once it sees ``count`` of them."""
    polygon = await system.messages("/perception/boxes", lambda m: len(m["points"]) == count, 30)
    return [(p["x"], p["y"]) for p in polygon["points"]]


@contextlib.asynccontextmanager
async def recording(system: LaunchedSystem, boxes: list[tuple[float, float]]) -> AsyncIterator[GroundTrack]:
    """Record the drone's ground track, read straight from the simulator, while inside."""
    track = GroundTrack(boxes)
    sim_url = f"http://127.0.0.1:{_base_port(system) + 1}"
    connected = asyncio.Event()

    async def read() -> None:
        async with connect(stream_url(sim_url, "/drone/pose", queue=10_000), max_size=None) as websocket:
            connected.set()
            async for frame in websocket:
                track.add(json.loads(frame))

    reader = asyncio.create_task(read())
    try:
        async with asyncio.timeout(10):
            while not connected.is_set():
                if reader.done():
                    await reader  # could not connect: say why
                await asyncio.sleep(0.01)
        yield track
    finally:
        reader.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            await reader


async def stop_launch(system: LaunchedSystem) -> None:
    """Ctrl-C a launch before the test ends, checked as the fixture checks it."""
    await asyncio.to_thread(conftest.stop_launch, system.process)
