"""The real system for browser tests: core and nodes as subprocesses started through the CLI.

Started exactly as a user would (``skydeck core``, ``skydeck run sim``, ``skydeck run control``)
on free loopback ports, each waited for on ``GET /health``, stopped with SIGTERM then SIGKILL.
"""

from __future__ import annotations

import os
import signal
import sys
from dataclasses import dataclass, field
from pathlib import Path

from services.launch.background import BackgroundProcess

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
        """Run ``skydeck ARGS --port PORT`` and wait until its ``/health`` answers 200."""
        background = BackgroundProcess(
            [sys.executable, "-m", "services.cli", *args, "--port", str(port)],
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
