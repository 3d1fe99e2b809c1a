"""The endpoints' ports: defaults, off with 0, on the flags of `skydeck core` and `skydeck
launch`, and a port in use (an endpoint's or the core's own) is one clear line at start-up.
(No test binds 9090 or 8765.)"""

from __future__ import annotations

import asyncio
import os
import socket
import sys

import httpx
import pytest

from services.launch.plan import LaunchOptions
from services.protocols.settings import CoreProcessSettings
from tests.conftest import free_port
from tests.services.protocols.conftest import Bridge

pytestmark = pytest.mark.timeout(60)


def test_defaults_are_the_tools_own_ports(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SKYDECK_ROSBRIDGE_PORT", raising=False)
    monkeypatch.delenv("SKYDECK_FOXGLOVE_PORT", raising=False)
    settings = CoreProcessSettings()
    assert (settings.rosbridge_port, settings.foxglove_port) == (9090, 8765)
    ports = LaunchOptions().core_endpoints()
    assert {endpoint.name: port for endpoint, port in ports.items()} == {"rosbridge": 9090, "foxglove": 8765}


async def run_cli(*args: str, timeout_s: float = 30.0) -> tuple[int, str]:
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", *args, env=dict(os.environ),
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
    )  # fmt: skip
    _, stderr = await asyncio.wait_for(process.communicate(), timeout_s)
    return process.returncode or 0, stderr.decode()


@pytest.fixture
def busy_port() -> object:
    with socket.socket() as taken:
        taken.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        taken.bind(("127.0.0.1", 0))
        taken.listen(1)
        yield taken.getsockname()[1]


async def test_a_busy_port_is_one_line_from_skydeck_core(busy_port: int) -> None:
    code, stderr = await run_cli("core", "--port", str(free_port()), "--rosbridge-port", str(busy_port), "--foxglove-port", "0")
    (line,) = stderr.splitlines()  # one line, nothing else
    assert code == 1 and line.startswith("skydeck: error: the rosbridge endpoint")
    assert f"rosbridge endpoint cannot listen on 127.0.0.1:{busy_port}" in line and "--rosbridge-port 0" in line


async def test_a_busy_core_port_is_one_line_before_anything_is_announced(busy_port: int) -> None:
    code, stderr = await run_cli("core", "--port", str(busy_port), "--rosbridge-port", "0", "--foxglove-port", "0")
    (line,) = stderr.splitlines()  # not the core's address first, not uvicorn's own error
    assert code == 1 and line.startswith("skydeck: error: the core cannot listen on")
    assert f"127.0.0.1:{busy_port}" in line and "--port" in line


async def test_a_busy_port_is_one_line_from_skydeck_launch(busy_port: int) -> None:
    base = free_port()
    code, stderr = await run_cli("launch", "--base-port", str(base), "--rosbridge-port", "0", "--foxglove-port", str(busy_port))
    (line,) = stderr.splitlines()  # one line, nothing else
    assert code == 1 and line.startswith("skydeck: error: ")
    assert f"port {busy_port} for the core's foxglove endpoint is already in use" in line and "--foxglove-port 0" in line


async def test_an_endpoint_port_greets_a_browser_and_0_turns_it_off(bridge: Bridge) -> None:
    async with httpx.AsyncClient() as http:
        greeting = await http.get(bridge.rosbridge_url.replace("ws", "http"))
        assert greeting.status_code == 200 and "rosbridge v2 endpoint" in greeting.text
        foxglove = await http.get(bridge.foxglove_url.replace("ws", "http"))
        assert "Foxglove WebSocket endpoint" in foxglove.text
    assert set(bridge.core.app.state.endpoints.ports) == {"rosbridge", "foxglove"}  # type: ignore[union-attr]


async def test_endpoints_off_bind_nothing(core) -> None:  # the suite's core: both ports 0
    assert core.app.state.endpoints.ports == {}
