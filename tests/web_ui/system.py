"""The real system for browser tests: core and nodes as subprocesses started through the CLI.

Started exactly as a user would (``skydeck core``, ``skydeck run sim``, ``skydeck run control``)
on free loopback ports, each waited for on ``GET /health``, stopped with SIGTERM then SIGKILL.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
STARTUP_TIMEOUT_S = 30.0




def _health(url: str) -> bool:
    try:
        with urllib.request.urlopen(f"{url}/health", timeout=1.0) as reply:
            return bool(reply.status == 200)
    except OSError:
        return False


@dataclass
class Process:
    """One process of the system, with its output kept in a log file for failure messages."""

    name: str
    url: str
    popen: subprocess.Popen[bytes]
    log_path: Path

    def log_tail(self, lines: int = 30) -> str:
        try:
            return "\n".join(self.log_path.read_text(errors="replace").splitlines()[-lines:])
        except OSError:
            return "(no log)"

    def stop(self) -> None:
        """SIGTERM, then SIGKILL if it does not exit within 5 s."""
        if self.popen.poll() is not None:
            return
        self.popen.send_signal(signal.SIGTERM)
        try:
            self.popen.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.popen.kill()
            self.popen.wait(timeout=5)


@dataclass
class System:
    """The running system: ``url`` is the core's, where the dashboard is served."""

    base_port: int
    log_dir: Path
    processes: dict[str, Process] = field(default_factory=dict)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.base_port}"

    @property
    def ws_url(self) -> str:
        return f"ws://127.0.0.1:{self.base_port}"

    def start(self, name: str, args: list[str], port: int, *, env: dict[str, str] | None = None) -> Process:
        """Run ``skydeck ARGS --port PORT`` and wait until its ``/health`` answers 200."""
        env = {**os.environ, "SKYDECK_CORE_URL": self.url, "PYTHONUNBUFFERED": "1", **(env or {})}
        log_path = self.log_dir / f"{name}.log"
        log = log_path.open("wb")
        popen = subprocess.Popen(
            [sys.executable, "-m", "services.cli", *args, "--port", str(port)],
            cwd=REPO,
            env=env,
            stdout=log,
            stderr=subprocess.STDOUT,
        )
        log.close()
        process = Process(name, f"http://127.0.0.1:{port}", popen, log_path)
        self.processes[name] = process
        deadline = time.monotonic() + STARTUP_TIMEOUT_S
        while not _health(process.url):
            if popen.poll() is not None:
                raise RuntimeError(f"`skydeck {' '.join(args)}` exited with {popen.returncode}:\n{process.log_tail()}")
            if time.monotonic() > deadline:
                raise RuntimeError(f"`skydeck {' '.join(args)}` not healthy after {STARTUP_TIMEOUT_S} s:\n{process.log_tail()}")
            time.sleep(0.1)
        return process

    def stop(self) -> None:
        for process in reversed(list(self.processes.values())):
            process.stop()
