"""The seed's two nodes, run the way a student runs them: `skydeck run examples/...`."""

from __future__ import annotations

import asyncio
import os
import signal
import sys
from pathlib import Path

import httpx

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


async def _run(core_url: str, path: Path) -> asyncio.subprocess.Process:
    return await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "run", str(path),
        env={**os.environ, "SKYDECK_CORE_URL": core_url, "PYTHONUNBUFFERED": "1"},
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
    )


async def _stop(process: asyncio.subprocess.Process) -> bytes:
    process.send_signal(signal.SIGINT)
    _, stderr = await asyncio.wait_for(process.communicate(), 10)
    return stderr


async def test_send_and_receive_message(core) -> None:
    sender = await _run(core.url, EXAMPLES / "send_message.py")
    receiver = await _run(core.url, EXAMPLES / "receive_message.py")
    try:
        assert receiver.stdout is not None
        line = await asyncio.wait_for(receiver.stdout.readline(), 15)
        # print(msg.header): the receiver shows each header, seq filled in by the publisher.
        assert b"frame_id='odom'" in line and b"seq=" in line
        async with httpx.AsyncClient() as http:
            point = (await http.get(core.url + "/my_point")).json()
        assert point["point"] == {"x": 1.0, "y": 2.0, "z": 0.0}
        assert point["header"]["frame_id"] == "odom"
    finally:
        for process in (receiver, sender):
            stderr = await _stop(process)
            assert b"Traceback" not in stderr, stderr.decode()
            assert process.returncode == 0


def test_sender_publishes_point_stamped_at_10_hz_on_my_point() -> None:
    import runpy

    namespace = runpy.run_path(str(EXAMPLES / "send_message.py"))
    node = namespace["SendMessageNode"]()
    # Rates are measured by the benchmark, not here: check what the node asks for.
    assert node.timer.timer_period_s == 0.1
    assert node.publisher.topic_name == "/my_point"
    assert node.publisher.msg_type.__ros_type__ == "geometry_msgs/msg/PointStamped"
