"""Running systems for the reliability tests.

- ``launch`` (from tests/e2e): a real `skydeck launch` per test, for killing processes.
- ``workshop``: one `skydeck launch` of the whole workshop system shared by the session, for the
  bad-input matrix and the fuzzer, which only need it to keep answering.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field

import httpx
import pytest

from tests.conftest import free_port_block
from tests.e2e.conftest import LaunchedSystem, launch

__all__ = ["LaunchedSystem", "Workshop", "launch", "workshop"]


@dataclass
class Workshop:
    """A launched workshop system: the core's URL and each node's own URL (from /api/graph)."""

    core_url: str
    node_urls: dict[str, str]
    lines: list[str] = field(default_factory=list)

    def graph(self) -> dict:
        return httpx.get(self.core_url + "/api/graph", timeout=5).json()  # type: ignore[no-any-return]

    def node_serves(self, node: str) -> bool:
        """The node answers /health on its own port and is still registered with the core."""
        health = httpx.get(self.node_urls[node] + "/health", timeout=5)
        return health.status_code == 200 and node in {n["name"] for n in self.graph()["nodes"]}


@pytest.fixture(scope="session")
def workshop(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Workshop]:
    base = free_port_block(5)
    env = {**os.environ, "SKYDECK_STATE_DIR": str(tmp_path_factory.mktemp("state")), "PYTHONUNBUFFERED": "1"}
    env.pop("SKYDECK_TOKEN", None)
    process = subprocess.Popen(
        [sys.executable, "-m", "services.cli", "launch", "--base-port", str(base), "--seed", "1"],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True,
    )
    lines: list[str] = []
    ready = threading.Event()

    def pump() -> None:
        assert process.stdout is not None
        for line in process.stdout:
            lines.append(line.rstrip("\n"))
            if line.startswith("[launch] all"):
                ready.set()
        ready.set()

    reader = threading.Thread(target=pump, daemon=True)
    reader.start()
    try:
        if not ready.wait(60) or process.poll() is not None:
            raise AssertionError("skydeck launch did not come up:\n" + "\n".join(lines[-30:]))
        core_url = f"http://127.0.0.1:{base}"
        deadline = time.monotonic() + 10
        while True:
            nodes = {n["name"]: n["url"] for n in httpx.get(core_url + "/api/graph", timeout=5).json()["nodes"]}
            if {"/sim", "/perception", "/control", "/ai"} <= nodes.keys() or time.monotonic() > deadline:
                break
            time.sleep(0.1)
        yield Workshop(core_url, nodes, lines)
    finally:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(20)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        reader.join(5)
    # Whatever the tests sent, no process printed a traceback (a handler that crashed).
    tracebacks = [i for i, line in enumerate(lines) if "Traceback" in line]
    assert not tracebacks, "\n".join(lines[tracebacks[0] - 5 : tracebacks[0] + 30])
