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
from dataclasses import dataclass, field
from pathlib import Path

from websockets.asyncio.client import connect

from services.bench.mission import GroundTrack
from services.runtime.links import stream_url
from tests.e2e.conftest import LaunchedSystem

__all__ = ["AiProcess", "ai_process", "box_positions", "recording", "stop_launch"]


def _base_port(system: LaunchedSystem) -> int:
    return int(system.core_url.rsplit(":", 1)[1])


@dataclass
class AiProcess:
    """`skydeck run ai` on the launch's AI port, and what it printed."""

    process: asyncio.subprocess.Process
    lines: list[str] = field(default_factory=list)


@contextlib.asynccontextmanager
async def ai_process(system: LaunchedSystem, state_dir: Path, *args: str) -> AsyncIterator[AiProcess]:
    """Run the AI beside a `skydeck launch --exclude ai`; stopped with Ctrl-C afterwards, and it
    must stop cleanly without a traceback."""
    env = {**os.environ, "SKYDECK_CORE_URL": system.core_url, "SKYDECK_STATE_DIR": str(state_dir), "PYTHONUNBUFFERED": "1"}
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "run", "ai", "--port", str(_base_port(system) + 4), "--use-sim-time", *args,
        env=env, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT, start_new_session=True,
    )  # fmt: skip
    ai = AiProcess(process)

    async def pump() -> None:
        assert process.stdout is not None
        async for raw in process.stdout:
            ai.lines.append(raw.decode(errors="replace").rstrip("\n"))

    reader = asyncio.create_task(pump())
    try:
        yield ai
    finally:
        if process.returncode is None:
            process.send_signal(signal.SIGINT)
            try:
                await asyncio.wait_for(process.wait(), 20)
            except TimeoutError:
                os.killpg(process.pid, signal.SIGKILL)
                raise AssertionError("skydeck run ai did not stop on Ctrl-C") from None
        await reader
    assert not any("Traceback" in line for line in ai.lines), "\n".join(ai.lines[-40:])
    assert process.returncode == 0, "\n".join(ai.lines[-20:])


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
    """Ctrl-C a launch before the test ends (the fixture checks how it stopped)."""
    system.process.send_signal(signal.SIGINT)
    await asyncio.wait_for(system.process.wait(), 20)
