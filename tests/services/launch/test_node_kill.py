"""`skydeck node kill` asks the launch, which stops the node for good, or says why not in a
machine-readable reason: a real launch, real nodes."""

from __future__ import annotations

import asyncio
import os
import signal
import sys
from pathlib import Path

import httpx
import pytest

from services.launch.background import BackgroundProcess
from services.launch.control import KILL_SERVICE
from shared_models.skydeck_launch import KillNodeResponse
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

        # Each refusal carries its reason, for programs; the message is for people.
        async def ask(node: str) -> KillNodeResponse:
            async with httpx.AsyncClient() as http:
                reply = await http.post(core_url + KILL_SERVICE, json={"node": node}, timeout=15)
            assert reply.status_code == 200, reply.text
            return KillNodeResponse.model_validate(reply.json())

        for node, reason in (
            ("/nobody", KillNodeResponse.UNKNOWN_NODE),
            ("/skydeck_core", KillNodeResponse.PROTECTED),
            ("/perception", KillNodeResponse.NOT_RUNNING),  # killed above: the launch knows it, stopped
        ):
            answer = await ask(node)
            assert (answer.success, answer.reason) == (False, reason) and node.strip("/") in answer.message, answer

        # A node this launch did not start: the launch says so (NOT_LAUNCHED), and `node kill`
        # then stops it itself, as it runs on this machine.
        outsider = BackgroundProcess(
            [sys.executable, "-m", "services.cli", "run", "examples/send_message.py", "--core-url", core_url,
             "--ros-args", "-r", "__node:=outsider"],
            name="outsider", env={**os.environ, "PYTHONUNBUFFERED": "1"},
        )  # fmt: skip
        try:
            async with asyncio.timeout(30):
                while "/outsider" not in await graph_nodes(core_url):
                    await asyncio.sleep(0.1)
            answer = await ask("/outsider")
            assert (answer.success, answer.reason) == (False, KillNodeResponse.NOT_LAUNCHED), answer
            status, out, err = await skydeck(core_url, "node", "kill", "/outsider")
            assert status == 0 and "killed /outsider (pid" in out and "with SIGTERM" in out, err
            assert await asyncio.to_thread(outsider.popen.wait, 15) == 0
        finally:
            outsider.stop()
    finally:
        assert await asyncio.to_thread(launch.stop, signal.SIGINT, 30)
    assert launch.returncode == 0 and not any("Traceback" in line for line in launch.lines), launch.tail()
