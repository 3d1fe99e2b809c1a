"""Two systems side by side, and a launch that finds a running core first (issue 32, items 5-6).

Real launches: ``skydeck launch --base-port B`` twice, 30 ports apart, each with its core's
protocol endpoints on their default ports moved with the base port (rosbridge B+1090, Foxglove
B+765); and ``skydeck launch`` with ``SKYDECK_CORE_URL`` pointing at a core already running, which
the launch joins instead of starting another. No test binds 9090 or 8765.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from websockets.asyncio.client import connect
from websockets.typing import Subprotocol

from services.launch.background import BackgroundProcess
from services.protocols.endpoints import ENDPOINTS
from services.runtime.ports import free_port_block, port_is_free
from tests.conftest import CoreProcess, wait_until

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(120)]

APART = 30
LAUNCH = """\
nodes:
  - name: core
    run: core
    port_offset: 0
  - name: perception
    run: perception
    port_offset: 1
"""


def _two_bases() -> int:
    """A base port B such that B.., B+APART.. and every endpoint moved from both are free (and
    none is 9090 or 8765)."""
    for _ in range(200):
        base = free_port_block(APART + 2)
        moved = [e.port_at(b) for e in ENDPOINTS for b in (base, base + APART)]
        if all(port <= 65535 and port not in (9090, 8765) and port_is_free(port) for port in moved):
            return base
    raise AssertionError("no free ports for two launches side by side")


def _environment(**extra: str) -> dict[str, str]:
    """This one without the suite's SKYDECK_*_PORT=0 (conftest.py): the endpoints take their
    ports as a user's launch does."""
    drop = {endpoint.env_var for endpoint in ENDPOINTS} | {"SKYDECK_CORE_URL"}
    return {**{k: v for k, v in os.environ.items() if k not in drop}, "PYTHONUNBUFFERED": "1", **extra}


@pytest.fixture
def launches() -> Iterator[list[BackgroundProcess]]:
    started: list[BackgroundProcess] = []
    yield started
    for process in started:
        assert process.stop(signal.SIGINT, timeout_s=20), f"{process.name} did not stop"
        assert not any("Traceback" in line for line in process.lines), process.tail(30)


async def test_two_launches_side_by_side_both_come_up_with_their_endpoints_moved(
    tmp_path: Path, launches: list[BackgroundProcess]
) -> None:
    path = tmp_path / "small.yaml"
    path.write_text(LAUNCH)
    first = _two_bases()
    for base in (first, first + APART):
        launches.append(
            BackgroundProcess(
                [sys.executable, "-m", "services.cli", "launch", str(path), "--base-port", str(base)],
                name=f"launch {base}",
                env=_environment(),
            )
        )
    for process, base in zip(launches, (first, first + APART), strict=True):
        await process.await_line("[launch] all 2 nodes up", 60)
        moved = {e.name: e.port_at(base) for e in ENDPOINTS}
        notice = ", ".join(f"{name} :{port}" for name, port in moved.items())
        assert f"[launch] protocol endpoints {notice} (moved with --base-port)" in process.lines, process.tail()
        async with httpx.AsyncClient() as http:
            health = (await http.get(f"http://127.0.0.1:{base}/health")).json()
        assert health["endpoints"] == moved
        async with connect(f"ws://127.0.0.1:{moved['rosbridge']}") as ws:
            await ws.send(json.dumps({"op": "call_service", "service": "/rosapi/get_ros_version", "id": "v"}))
            answer = json.loads(await ws.recv())
            assert answer["result"] is True and answer["values"]["version"] == 2
        async with connect(f"ws://127.0.0.1:{moved['foxglove']}", subprotocols=[Subprotocol("foxglove.websocket.v1")]) as ws:
            assert json.loads(await ws.recv())["op"] == "serverInfo"


async def test_a_launch_joins_the_core_at_skydeck_core_url_instead_of_starting_one(
    tmp_path: Path, launches: list[BackgroundProcess]
) -> None:
    """As roslaunch with ROS_MASTER_URI: no --base-port, a core answering at SKYDECK_CORE_URL;
    the launch starts only its nodes (on ports from that core's), which register with it."""
    base = free_port_block(3)
    core = CoreProcess(base)  # endpoints off, as every core of the suite
    await core.start()
    try:
        path = tmp_path / "small.yaml"
        path.write_text(LAUNCH)
        process = BackgroundProcess(
            [sys.executable, "-m", "services.cli", "launch", str(path)],
            name="launch joining",
            env=_environment(SKYDECK_CORE_URL=core.url),
        )
        launches.append(process)
        await process.await_line("[launch] all 1 nodes up", 60)
        assert f"[launch] a core answers at {core.url}: the launch joins it" in process.lines
        assert f"[launch] starting perception :{base + 1}; core at {core.url}" in process.lines
        await wait_until(lambda: "/perception" in core.registry.nodes, 10, "perception to register with the core")
        assert process.stop(signal.SIGINT, timeout_s=20)
        launches.clear()
        assert not any("Traceback" in line for line in process.lines), process.tail(30)
    finally:
        await core.stop()


def test_a_launch_does_not_start_a_core_for_another_machines_url(tmp_path: Path) -> None:
    path = tmp_path / "small.yaml"
    path.write_text(LAUNCH)
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "launch", str(path)],
        env=_environment(SKYDECK_CORE_URL="http://192.0.2.1:8000"),  # TEST-NET-1: nobody answers
        capture_output=True, text=True, timeout=60, check=False,
    )  # fmt: skip
    assert done.returncode == 1, done.stderr
    (line,) = done.stderr.splitlines()
    assert line.startswith("skydeck: error: no core answers at SKYDECK_CORE_URL=http://192.0.2.1:8000")
    assert "unset SKYDECK_CORE_URL (or give --base-port)" in line
