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

from services.launch.background import BackgroundProcess
from services.protocols.endpoints import ENDPOINTS
from services.runtime.edge.links import stream_url
from tests.conftest import free_port_block


@dataclass
class LaunchedSystem:
    """A running `skydeck launch` (a BackgroundProcess) and what it printed."""

    process: BackgroundProcess
    core_url: str
    pids: set[int] = field(default_factory=set)

    @property
    def lines(self) -> list[str]:
        return self.process.lines

    async def wait_for_line(self, text: str, timeout_s: float = 60.0, *, after: int = 0) -> int:
        """Wait until a printed line (from index ``after`` on) contains ``text``; its index."""
        return await self.process.await_line(text, timeout_s, after=after)

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


def start_launch(
    *args: str, state_dir: Path, env: dict[str, str] | None = None, unset: tuple[str, ...] = ()
) -> tuple[BackgroundProcess, str]:
    """`skydeck launch --base-port B ARGS` on free ports (not yet waited for); its core's URL.

    Its environment is this one, with ``env`` added and the variables in ``unset`` removed.
    """
    base = free_port_block(5)
    environment = {**os.environ, "SKYDECK_STATE_DIR": str(state_dir), "PYTHONUNBUFFERED": "1", **(env or {})}
    for variable in unset:
        environment.pop(variable, None)
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "launch", "--base-port", str(base), *_endpoints_off(args), *args],
        name="skydeck launch",
        env=environment,
    )
    return process, f"http://127.0.0.1:{base}"


def _endpoints_off(args: tuple[str, ...]) -> list[str]:
    """The core's protocol endpoints off unless ``args`` set their ports (never 9090/8765 here)."""
    return [part for endpoint in ENDPOINTS if endpoint.flag not in args for part in (endpoint.flag, "0")]


def stop_launch(process: BackgroundProcess) -> None:
    """Ctrl-C, as a user would; the launch must stop cleanly, with no traceback printed."""
    stopped = process.stop(signal.SIGINT, timeout_s=20)
    assert stopped, "skydeck launch did not stop on Ctrl-C"
    tracebacks = [i for i, line in enumerate(process.lines) if "Traceback" in line]
    assert not tracebacks, "\n".join(process.lines[max(tracebacks[0] - 5, 0) : tracebacks[0] + 30])
    assert process.returncode == 0, process.tail(20)


@pytest.fixture
async def launch(tmp_path: Path) -> AsyncIterator[Callable[..., Awaitable[LaunchedSystem]]]:
    """Start `skydeck launch ARGS` on free ports; stopped with Ctrl-C (SIGINT) afterwards."""
    systems: list[LaunchedSystem] = []

    async def start(*args: str, env: dict[str, str] | None = None) -> LaunchedSystem:
        process, core_url = start_launch(*args, state_dir=tmp_path / "state", env=env)
        system = LaunchedSystem(process, core_url)
        systems.append(system)
        await system.wait_for_line("[launch] all", timeout_s=60)
        system.pids = {node["pid"] for node in (await system.graph())["nodes"]}
        return system

    yield start
    for system in systems:
        await asyncio.to_thread(stop_launch, system.process)
        for pid in system.pids:
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
