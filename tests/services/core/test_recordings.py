"""Recording from the dashboard's API: the core records, lists and serves MCAP files."""

from __future__ import annotations

import asyncio
import os
import signal
import sys

import httpx
from websockets.asyncio.client import connect

from services.bag import BagReader
from services.launch.background import BackgroundProcess
from services.runtime.edge.links import stream_url
from shared_models.geometry_msgs import Twist, Vector3
from tests.conftest import CoreProcess, free_port, wait_until
from tests.services.bag.test_record_play import Talker


async def test_start_record_stop_list_and_download(tmp_path) -> None:
    core = CoreProcess(recordings_dir=tmp_path / "recordings", token="secret")
    await core.start()
    auth = {"Authorization": "Bearer secret"}
    talker = await start_node_on(core, Talker)
    try:
        async with httpx.AsyncClient(base_url=core.url, timeout=10) as http:
            assert (await http.post("/api/recordings", json={})).status_code == 401  # acting needs the token
            started = await http.post("/api/recordings", json={"exclude": "_text$"}, headers=auth)
            assert started.status_code == 200 and started.json()["recording"] is True
            name = started.json()["name"]
            again = await http.post("/api/recordings", headers=auth)
            assert again.status_code == 409 and "already recording" in again.json()["detail"]
            await wait_until(lambda: talker.publisher.get_subscription_count() == 1, what="the core to link")
            talker.send(120)
            # A client publishing through the core is recorded too (the dashboard's teleop).
            async with connect(stream_url(core.url, "/drone/cmd_vel", type="geometry_msgs/msg/Twist", token="secret")) as ws:
                await ws.send(Twist(linear=Vector3(x=0.5)).model_dump_json())  # the topic appears: -a finds it
                await wait_until(lambda: "/drone/cmd_vel" in core.app.state.recordings.status()["topics"], what="the topic")
                await ws.send(Twist(linear=Vector3(x=0.7)).model_dump_json())
                await wait_until(lambda: core.app.state.recordings.status()["topics"]["/drone/cmd_vel"] == 1, what="the twist")
            await wait_until(lambda: core.app.state.recordings.status()["topics"].get("/points") == 120, what="120 points")
            listing = (await http.get("/api/recordings")).json()
            assert listing["current"]["recording"] and listing["files"][0]["name"] == name and listing["files"][0]["recording"]
            stopped = await http.post("/api/recordings/stop", headers=auth)
            assert stopped.status_code == 200 and stopped.json()["messages"] >= 121 and not stopped.json()["recording"]
            assert (await http.post("/api/recordings/stop", headers=auth)).status_code == 409
            download = await http.get(f"/api/recordings/{name}")
            assert download.status_code == 200 and download.content == (tmp_path / "recordings" / name).read_bytes()
            assert f'filename="{name}"' in download.headers["content-disposition"]
            for bad in ("nope.mcap", "..%2Fsecret.mcap", "notes.txt"):
                assert (await http.get(f"/api/recordings/{bad}")).status_code == 404
            bad_regex = await http.post("/api/recordings", json={"exclude": "("}, headers=auth)
            assert bad_regex.status_code == 400 and "not a regular expression" in bad_regex.json()["detail"]
        with BagReader(tmp_path / "recordings" / name) as bag:
            assert not bag.summary.recovered and bag.summary.topic("/points").count == 120
            assert bag.summary.topic("/points_text") is None and bag.summary.topic("/drone/cmd_vel").count == 1
    finally:
        await talker.stop()
        await core.stop()


async def test_a_recording_in_progress_is_finished_when_the_core_stops(tmp_path) -> None:
    """A real `skydeck core`, stopped with SIGTERM as a launch or docker stops it."""
    port = free_port()
    env = {**os.environ, "SKYDECK_RECORDINGS_DIR": str(tmp_path), "PYTHONUNBUFFERED": "1"}
    core = BackgroundProcess([sys.executable, "-m", "services.cli", "core", "--port", str(port)], name="core", env=env)
    try:
        await asyncio.to_thread(core.wait_healthy, f"http://127.0.0.1:{port}/health", 30)
        async with httpx.AsyncClient(base_url=f"http://127.0.0.1:{port}", timeout=10) as http:
            name = (await http.post("/api/recordings", json={"topics": ["/points"], "max_duration_s": 60})).json()["name"]
            assert (await http.get("/api/recordings")).json()["folder"] == str(tmp_path)
    finally:
        assert await asyncio.to_thread(core.stop, signal.SIGTERM, 20)
    with BagReader(tmp_path / name) as bag:
        assert not bag.summary.recovered and bag.summary.message_count == 0


async def start_node_on(core, factory):  # type: ignore[no-untyped-def]
    """Start a node against ``core`` (not the fixture's core)."""
    from services.runtime import NodeSettings

    node = factory(NodeSettings(core_url=core.url, port=0, token="secret"))
    await node.start()
    await wait_until(lambda: node.get_name() in core.registry.nodes, what="the node to register")
    return node


async def test_a_body_that_is_not_utf8_json_is_a_422_like_any_bad_body(core) -> None:
    async with httpx.AsyncClient(base_url=core.url) as http:
        for body in (b"l\x060L\xff\xfeE\xc2\x81", b'{"topics": 3}'):
            reply = await http.post("/api/recordings", content=body, headers={"content-type": "application/json"})
            assert reply.status_code == 422, reply.text
            assert reply.json()["detail"][0]["loc"][0] == "body"
        assert (await http.get("/api/recordings/no-such.mcap")).status_code == 404  # other HTTP errors keep theirs
