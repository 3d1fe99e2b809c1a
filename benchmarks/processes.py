"""The benchmark's worker processes: spawned with ``sys.executable``, one JSON line each way
(on :class:`~services.launch.background.BackgroundProcess`, the harness the tests use too).

A worker prints ``READY {json}`` when it can be measured and ``RESULT {json}`` when it is done;
it reads commands (``stop``) on stdin. Its stderr goes to a log file whose tail is shown when
the worker fails, so a broken benchmark says why instead of hanging.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from services.launch.background import BackgroundProcess, ProcessFailed
from services.runtime.ports import free_port_block
from shared_models.errors import SkydeckError

__all__ = ["BenchError", "Worker", "free_port", "start_core", "wait_http", "worker_env"]

_LOG_DIR = Path(tempfile.gettempdir()) / "skydeck-bench"


class BenchError(SkydeckError):
    """A benchmark could not be measured (a worker failed, timed out, or never got ready)."""


def free_port() -> int:
    """A TCP port free on loopback right now."""
    return free_port_block(1)


def worker_env(core_url: str | None = None, **extra: str) -> dict[str, str]:
    """The environment of a worker: quiet logs, and the core's URL when it needs one."""
    env = dict(os.environ)
    env["SKYDECK_LOG_LEVEL"] = "WARNING"
    env["PYTHONUNBUFFERED"] = "1"
    # A core the bench starts leaves the well-known endpoint ports (9090, 8765) alone: other runs
    # and a user's own launch may use them. The rosbridge rows give their core a free port.
    env["SKYDECK_ROSBRIDGE_PORT"] = "0"
    env["SKYDECK_FOXGLOVE_PORT"] = "0"
    if core_url is not None:
        env["SKYDECK_CORE_URL"] = core_url
    env.update(extra)
    return env


class Worker(BackgroundProcess):
    """One spawned process; ``python -m MODULE ARGS`` unless ``argv`` is given whole.

    Its stdout carries the protocol (``READY``/``RESULT`` lines); stderr goes to a log file whose
    tail is shown when the worker fails.
    """

    def __init__(
        self,
        name: str,
        module: str | None = None,
        *args: str,
        argv: list[str] | None = None,
        env: dict[str, str] | None = None,
    ) -> None:
        _LOG_DIR.mkdir(parents=True, exist_ok=True)
        super().__init__(
            argv if argv is not None else [sys.executable, "-m", str(module), *args],
            name=name,
            env=env or worker_env(),
            log_path=_LOG_DIR / f"{name}-{os.getpid()}-{time.monotonic_ns()}.log",
            stdin=True,
        )

    def expect(self, tag: str, timeout_s: float) -> dict[str, Any]:
        """Wait for the line ``TAG {json}`` and return its JSON; raises BenchError otherwise."""
        try:
            index = self.wait_for_line(lambda line: line.partition(" ")[0] == tag, timeout_s)
        except ProcessFailed as error:
            raise BenchError(str(error)) from None
        body = self.lines[index].partition(" ")[2]
        return json.loads(body) if body else {}

    def __enter__(self) -> Worker:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop(timeout_s=5.0)


def wait_http(url: str, timeout_s: float, *, what: str, worker: Worker) -> None:
    """Wait until ``url`` answers 200 while ``worker`` runs; raises BenchError after ``timeout_s``."""
    try:
        worker.wait_healthy(url, timeout_s)
    except ProcessFailed as error:
        raise BenchError(f"{what}: {error}") from None


def start_core(
    name: str = "core", *, rosbridge_port: int = 0, flags: tuple[str, ...] = (), env: dict[str, str] | None = None
) -> tuple[Worker, str]:
    """A ``skydeck core`` on a free port, serving; returns the worker and its URL.

    Its protocol endpoints are off, but for rosbridge on ``rosbridge_port`` when one is given;
    ``flags`` are more of its flags (``--class-tokens FILE``), ``env`` its environment.
    """
    port = free_port()
    endpoints = ["--rosbridge-port", str(rosbridge_port), "--foxglove-port", "0"]
    worker = Worker(
        name, "services.cli", "core", "--port", str(port), "--log-level", "warning", *endpoints, *flags,
        env=env or worker_env(),
    )  # fmt: skip
    url = f"http://127.0.0.1:{port}"
    try:
        wait_http(f"{url}/health", 20.0, what="skydeck core", worker=worker)
    except BenchError:
        worker.stop()
        raise
    return worker, url
