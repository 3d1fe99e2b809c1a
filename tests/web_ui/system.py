"""The real system for browser tests: core and nodes as subprocesses started through the CLI.

Started exactly as a user would (``skydeck core``, ``skydeck run sim``, ``skydeck run control``)
on free loopback ports, each waited for on ``GET /health``, stopped with SIGTERM then SIGKILL.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from services.launch.background import BackgroundProcess
from tests.conftest import free_port_block

REPO = Path(__file__).resolve().parents[2]
STARTUP_TIMEOUT_S = 30.0


@dataclass
class Process:
    """One process of the system and where it serves."""

    name: str
    url: str
    background: BackgroundProcess

    def stop(self) -> None:
        """SIGTERM, then SIGKILL if it does not exit within 5 s."""
        self.background.stop(signal.SIGTERM, timeout_s=5)


@dataclass
class System:
    """The running system: ``url`` is the core's, where the dashboard is served."""

    base_port: int
    processes: dict[str, Process] = field(default_factory=dict)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.base_port}"

    @property
    def ws_url(self) -> str:
        return f"ws://127.0.0.1:{self.base_port}"

    def start(self, name: str, args: list[str], port: int, *, env: dict[str, str] | None = None) -> Process:
        """Run ``skydeck ARGS --port PORT`` and wait until its ``/health`` answers 200 (a core
        without its protocol endpoints: the suite never binds their well-known ports)."""
        endpoints = ["--rosbridge-port", "0", "--foxglove-port", "0"] if args[:1] == ["core"] else []
        background = BackgroundProcess(
            [sys.executable, "-m", "services.cli", *args, "--port", str(port), *endpoints],
            name=f"`skydeck {' '.join(args)}`",
            cwd=REPO,
            env={**os.environ, "SKYDECK_CORE_URL": self.url, "PYTHONUNBUFFERED": "1", **(env or {})},
        )
        process = Process(name, f"http://127.0.0.1:{port}", background)
        self.processes[name] = process
        background.wait_healthy(f"{process.url}/health", STARTUP_TIMEOUT_S)
        return process

    def stop(self) -> None:
        for process in reversed(list(self.processes.values())):
            process.stop()


def answered(service: str) -> str:
    """A page predicate: the dashboard's last command is ``service`` and has its answer."""
    return (
        "() => { const r = window.skydeck.lastCommand; "
        f"return r && r.service === '{service}' && r.kind !== 'pending'; }}"
    )


@contextlib.contextmanager
def started(*processes: tuple[str, list[str]]) -> Iterator[System]:
    """The core and the given processes (``(name, skydeck args)``) on P, P+1, ...; stopped after."""
    base = free_port_block(5)
    running = System(base)
    try:
        running.start("core", ["core"], base)
        for offset, (name, args) in enumerate(processes, start=1):
            running.start(name, args, base + offset)
        yield running
    finally:
        running.stop()
