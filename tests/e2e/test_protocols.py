"""The workshop system driven by the tools robotics people already have: roslibpy over the
rosbridge endpoint flies the real drone, and Foxglove's client reads the simulator's topics."""

from __future__ import annotations

import asyncio
import json
import sys
from pathlib import Path

import pytest
from websockets.asyncio.client import connect

from tests.conftest import free_port

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(180)]

CLIENTS = Path(__file__).resolve().parents[1] / "clients"


async def test_roslibpy_flies_the_drone_and_foxglove_sees_the_world(launch) -> None:
    rosbridge, foxglove = free_port(), free_port()
    system = await launch("--speed", "4",  # the whole workshop, as `make up`: the AI waits for /ai/start
                          "--rosbridge-port", str(rosbridge), "--foxglove-port", str(foxglove))  # fmt: skip
    process = await asyncio.create_subprocess_exec(
        sys.executable, str(CLIENTS / "roslibpy_client.py"), f"ws://127.0.0.1:{rosbridge}", "workshop",
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
    )  # fmt: skip
    out, err = await asyncio.wait_for(process.communicate(), 120)
    assert process.returncode == 0, err.decode()[-3000:]
    lines = {key: value for line in out.decode().splitlines() for key, value in json.loads(line).items()}
    assert lines["connected"] is True
    assert lines["pose"]["header"]["frame_id"] == "map"
    assert lines["take_off"] == {"success": True, "message": "All ok!"}, lines["take_off"]  # as docs/protocols.md says
    assert lines["climbed"] is True and lines["top"] > 2.0
    assert {"/drone/pose", "/simulator/boxes", "/clock"} <= set(lines["topics"])

    async with connect(f"ws://127.0.0.1:{foxglove}", subprotocols=["foxglove.websocket.v1"], max_size=None) as ws:  # type: ignore[list-item]
        info = json.loads(await ws.recv())
        assert info["op"] == "serverInfo" and "time" in info["capabilities"]  # the simulator's clock
        channels = {}
        while "/simulator/boxes" not in channels:
            message = json.loads(await ws.recv())
            if message["op"] == "advertise":
                channels.update({c["topic"]: c for c in message["channels"]})
        boxes = channels["/simulator/boxes"]
        assert boxes["schemaName"] == "geometry_msgs/msg/PoseArray"
        await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": boxes["id"]}]}))
        async with asyncio.timeout(20):
            while True:
                frame = await ws.recv()
                if isinstance(frame, bytes) and frame[0] == 1:
                    break
        payload = json.loads(frame[13:])
        assert len(payload["poses"]) == 8 and payload["header"]["stamp"]["nsec"] == payload["header"]["stamp"]["nanosec"]
    assert system.core_url
