"""`skydeck node kill` asks the launch, which stops the node for good: a real launch, real nodes."""

from __future__ import annotations

import asyncio
import os
import signal
import sys
from pathlib import Path

import httpx
import pytest

from services.launch.background import BackgroundProcess
from tests.conftest import free_port_block
from tests.services.cli.test_cli import skydeck

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(120)]

LAUNCH = """
nodes:
  - name: core
    run: core
    port_offset: 0
  - name: perception
    run: perception
    port_offset: 1
  - name: talker
    run: {example}
    port_offset: 2
"""


async def graph_nodes(core_url: str) -> set[str]:
    async with httpx.AsyncClient() as http:
        return {node["name"] for node in (await http.get(core_url + "/api/graph", timeout=5)).json()["nodes"]}


async def test_a_killed_node_is_not_respawned_while_a_crashed_one_is(tmp_path: Path) -> None:
    launch_file = tmp_path / "small.yaml"
    launch_file.write_text(LAUNCH.format(example=Path("examples/send_message.py").resolve()))
    base = free_port_block(3)
    core_url = f"http://127.0.0.1:{base}"
    launch = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "launch", str(launch_file), "--base-port", str(base)],
        name="launch", env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )
    try:
        await launch.await_line("[launch] all 3 nodes up", 60)
        assert {"/perception", "/send_message_node", "/skydeck_launch"} <= await graph_nodes(core_url)
        status, out, err = await skydeck(core_url, "node", "kill", "/perception")
        assert status == 0 and "killed /perception (launch node perception, pid" in out and "not respawned" in out, err
        said = await launch.await_line("perception killed on request (skydeck node kill); not respawned", 20)
        # A crash, by contrast, is respawned; by the time it is, a respawn of perception would have come too.
        async with httpx.AsyncClient() as http:
            talker = (await http.get(core_url + "/api/nodes/send_message_node", timeout=5)).json()
        os.kill(talker["pid"], signal.SIGKILL)
        await launch.await_line("talker ready at", 30, after=said)
        assert not any("perception ready" in line for line in launch.lines[said:]), launch.tail()
        assert "/perception" not in await graph_nodes(core_url)
        status, _, err = await skydeck(core_url, "node", "kill", "/skydeck_launch")
        assert status == 1 and "part of Skydeck itself" in err
    finally:
        assert await asyncio.to_thread(launch.stop, signal.SIGINT, 30)
    assert launch.returncode == 0 and not any("Traceback" in line for line in launch.lines), launch.tail()
