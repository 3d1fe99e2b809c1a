"""The benchmark's worker processes: spawned with ``sys.executable``, one JSON line each way.

A worker prints ``READY {json}`` when it can be measured and ``RESULT {json}`` when it is done;
it reads commands (``stop``) on stdin. Its stderr goes to a log file whose tail is shown when
the worker fails, so a broken benchmark says why instead of hanging.
"""

from __future__ import annotations

import contextlib
import json
import os
import queue
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import httpx

from services.runtime.ports import free_port_block

__all__ = ["BenchError", "Worker", "free_port", "start_core", "wait_http", "worker_env"]

_LOG_DIR = Path(tempfile.gettempdir()) / "skydeck-bench"


class BenchError(Exception):
    """A benchmark could not be measured (a worker failed, timed out, or never got ready)."""


def free_port() -> int:
    """A TCP port free on loopback right now."""
    return free_port_block(1)


def worker_env(core_url: str | None = None, **extra: str) -> dict[str, str]:
    """The environment of a worker: quiet logs, and the core's URL when it needs one."""
    env = dict(os.environ)
    env["SKYDECK_LOG_LEVEL"] = "WARNING"
    env["PYTHONUNBUFFERED"] = "1"
    if core_url is not None:
        env["SKYDECK_CORE_URL"] = core_url
    env.update(extra)
    return env


class Worker:
    """One spawned process; ``python -m MODULE ARGS`` unless ``argv`` is given whole."""

    def __init__(
        self,
        name: str,
        module: str | None = None,
        *args: str,
        argv: list[str] | None = None,
        env: dict[str, str] | None = None,
    ) -> None:
        self.name = name
        command = argv if argv is not None else [sys.executable, "-m", str(module), *args]
        _LOG_DIR.mkdir(parents=True, exist_ok=True)
        self.log_path = _LOG_DIR / f"{name}-{os.getpid()}-{time.monotonic_ns()}.log"
        self._log = self.log_path.open("w")
        self.process = subprocess.Popen(
            command,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self._log,
            text=True,
            env=env or worker_env(),
            start_new_session=True,  # its own process group: stopping it stops its children
        )
        self._lines: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    @property
    def pid(self) -> int:
        return self.process.pid

    def _read(self) -> None:
        stdout = self.process.stdout
        if stdout is None:
            return
        for line in stdout:
            self._lines.put(line.rstrip("\n"))
        self._lines.put(None)

    def expect(self, tag: str, timeout_s: float) -> dict[str, Any]:
        """Wait for the line ``TAG {json}`` and return its JSON; raises BenchError otherwise."""
        deadline = time.monotonic() + timeout_s
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise BenchError(f"{self.name}: no {tag} within {timeout_s:g} s{self._tail()}")
            try:
                line = self._lines.get(timeout=left)
            except queue.Empty:
                continue
            if line is None:
                self.process.wait()
                raise BenchError(
                    f"{self.name} exited ({self.process.returncode}) before {tag}{self._tail()}"
                )
            head, _, body = line.partition(" ")
            if head == tag:
                return json.loads(body) if body else {}

    def send(self, command: str) -> None:
        """Write one command line to the worker's stdin."""
        stdin = self.process.stdin
        if stdin is None or stdin.closed:
            return
        with contextlib.suppress(BrokenPipeError, OSError):
            stdin.write(command + "\n")
            stdin.flush()

    def stop(self, timeout_s: float = 5.0) -> None:
        """SIGINT its process group, then SIGKILL if it lingers; idempotent."""
        if self.process.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self.process.pid, signal.SIGINT)
            try:
                self.process.wait(timeout_s)
            except subprocess.TimeoutExpired:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(self.process.pid, signal.SIGKILL)
                self.process.wait()
        for stream in (self.process.stdin, self.process.stdout):
            with contextlib.suppress(OSError):
                if stream is not None:
                    stream.close()
        self._log.close()

    def cpu_seconds(self) -> float:
        """User + system CPU time of the process so far (Linux /proc)."""
        return _cpu_seconds(self.process.pid)

    def _tail(self, lines: int = 15) -> str:
        self._log.flush()
        try:
            text = self.log_path.read_text(errors="replace").strip().splitlines()[-lines:]
        except OSError:
            return ""
        return (":\n    " + "\n    ".join(text)) if text else ""

    def __enter__(self) -> Worker:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


def _cpu_seconds(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as stat:
        fields = stat.read().rpartition(")")[2].split()
    # Fields after the command: state is [0], utime [11], stime [12] (clock ticks).
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def wait_http(url: str, timeout_s: float, *, what: str, worker: Worker | None = None) -> None:
    """Poll ``url`` until it answers 200; raises BenchError after ``timeout_s``."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if worker is not None and worker.process.poll() is not None:
            raise BenchError(f"{what} exited ({worker.process.returncode}){worker._tail()}")
        with contextlib.suppress(httpx.HTTPError):
            if httpx.get(url, timeout=1.0).status_code == 200:
                return
        time.sleep(0.02)
    raise BenchError(f"{what} did not answer {url} within {timeout_s:g} s")


def start_core(name: str = "core") -> tuple[Worker, str]:
    """A ``skydeck core`` on a free port, serving; returns the worker and its URL."""
    port = free_port()
    worker = Worker(
        name, "services.cli", "core", "--port", str(port), "--log-level", "warning", env=worker_env()
    )
    url = f"http://127.0.0.1:{port}"
    try:
        wait_http(f"{url}/health", 20.0, what="skydeck core", worker=worker)
    except BenchError:
        worker.stop()
        raise
    return worker, url
