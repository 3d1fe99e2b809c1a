"""The whole system started the way a user starts it: `skydeck launch`, as a subprocess."""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import sys
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import dataclass, field
from pathlib import Path

import httpx
import pytest
from websockets.asyncio.client import connect

from services.runtime.links import stream_url
from tests.conftest import free_port_block


@dataclass
class LaunchedSystem:
    """A running `skydeck launch` and what it printed."""

    process: asyncio.subprocess.Process
    core_url: str
    lines: list[str] = field(default_factory=list)
    _line_added: asyncio.Event = field(default_factory=asyncio.Event)

    async def wait_for_line(self, text: str, timeout_s: float = 60.0, *, after: int = 0) -> int:
        """Wait until a printed line (from index ``after`` on) contains ``text``; its index."""
        async with asyncio.timeout(timeout_s):
            while True:
                for index in range(after, len(self.lines)):
                    if text in self.lines[index]:
                        return index
                self._line_added.clear()
                await self._line_added.wait()

    async def graph(self) -> dict:
        async with httpx.AsyncClient() as http:
            return (await http.get(self.core_url + "/api/graph", timeout=5)).json()

    async def call(self, name: str, body: dict | None = None) -> dict:
        async with httpx.AsyncClient() as http:
            reply = await http.post(self.core_url + name, json=body or {}, timeout=10)
        reply.raise_for_status()
        return reply.json()

    async def messages(self, topic: str, until: Callable[[dict], bool], timeout_s: float) -> dict:
        """Read ``topic`` through the gateway until a message satisfies ``until``; that message."""
        async with asyncio.timeout(timeout_s), connect(stream_url(self.core_url, topic), max_size=None) as websocket:
            async for frame in websocket:
                message = json.loads(frame)
                if until(message):
                    return message
        raise AssertionError(f"{topic} ended")


@pytest.fixture
async def launch(tmp_path: Path) -> AsyncIterator[Callable[..., Awaitable[LaunchedSystem]]]:
    """Start `skydeck launch ARGS` on free ports; stopped with Ctrl-C (SIGINT) afterwards."""
    systems: list[LaunchedSystem] = []

    async def start(*args: str, env: dict[str, str] | None = None) -> LaunchedSystem:
        base = free_port_block(5)
        process = await asyncio.create_subprocess_exec(
            sys.executable, "-m", "services.cli", "launch", "--base-port", str(base), *args,
            env={**os.environ, "SKYDECK_STATE_DIR": str(tmp_path / "state"), "PYTHONUNBUFFERED": "1", **(env or {})},
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
            start_new_session=True,
        )
        system = LaunchedSystem(process, f"http://127.0.0.1:{base}")
        systems.append(system)

        async def pump() -> None:
            assert process.stdout is not None
            async for raw in process.stdout:
                system.lines.append(raw.decode(errors="replace").rstrip("\n"))
                system._line_added.set()

        system._pump = asyncio.create_task(pump())  # type: ignore[attr-defined]
        await system.wait_for_line("[launch] all", timeout_s=60)
        system.pids = {node["pid"] for node in (await system.graph())["nodes"]}  # type: ignore[attr-defined]
        return system

    yield start
    for system in systems:
        if system.process.returncode is None:
            system.process.send_signal(signal.SIGINT)
            try:
                await asyncio.wait_for(system.process.wait(), 20)
            except TimeoutError:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(system.process.pid, signal.SIGKILL)
                raise AssertionError("skydeck launch did not stop on Ctrl-C") from None
        await system._pump  # type: ignore[attr-defined]
        assert not any("Traceback" in line for line in system.lines), "\n".join(system.lines[-40:])
        assert system.process.returncode == 0, "\n".join(system.lines[-20:])
        for pid in system.pids:  # type: ignore[attr-defined]
            assert not _alive(pid), f"pid {pid} outlived skydeck launch"


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # A zombie is gone for our purposes; /proc says so.
    with contextlib.suppress(OSError):
        return " Z " not in open(f"/proc/{pid}/stat").read()
    return False
