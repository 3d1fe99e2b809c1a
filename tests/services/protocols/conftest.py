"""A core with both protocol endpoints on free ports, a small drone node, and the real clients.

The clients are the ones users have: roslibpy (PyPI) and, through Node, roslib and
@foxglove/ws-protocol (npm, tests/clients). Each runs as its own process with a scenario script
(tests/clients/*.py, *.mjs) that prints one JSON object per line.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import shutil
import sys
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from services.runtime import Node, NodeSettings
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, Pose, PoseStamped, Twist
from shared_models.std_msgs import Header, String
from shared_models.std_srvs import Trigger, TriggerResponse
from tests.conftest import CoreProcess, listening_socket, wait_until

CLIENTS = Path(__file__).resolve().parents[2] / "clients"
NODE = shutil.which("node")


class Drone(Node):
    """Publishes /drone/pose (20 Hz, stamped) and a latched /drone/name; follows /drone/cmd_vel;
    serves /control/take_off; /clock while ``clock`` is set."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("drone", settings=settings)
        self.z = 0.0
        self.commands: list[Twist] = []
        self.pose = self.create_publisher(PoseStamped, "/drone/pose", 10)
        self.name = self.create_publisher(String, "/drone/name", 1, latched=True)
        self.clock = self.create_publisher(Time, "/clock", 10)
        self.create_subscription(Twist, "/drone/cmd_vel", self.commands.append, 10)
        self.create_service(Trigger, "/control/take_off", self.take_off)
        self.create_timer(0.05, self.tick)
        self.ticks = 0
        self.name.publish(String(data="iris"))

    def tick(self) -> None:
        self.ticks += 1
        stamp = Time(sec=100 + self.ticks // 20, nanosec=(self.ticks % 20) * 50_000_000)
        self.clock.publish(stamp)
        self.pose.publish(
            PoseStamped(header=Header(stamp=stamp, frame_id="map"), pose=Pose(position=Point(x=1.0, y=2.0, z=self.z)))
        )

    def take_off(self, request: Any) -> TriggerResponse:
        if self.z <= 0.1:
            self.z = 3.0
            return TriggerResponse(success=True, message="All ok!")
        return TriggerResponse(success=False, message="Seems like the drone is already flying!")


@dataclass
class Bridge:
    """The core (with its endpoints' URLs) and the drone node."""

    core: CoreProcess
    drone: Drone
    rosbridge_url: str
    foxglove_url: str
    token: str = ""
    processes: list[asyncio.subprocess.Process] = field(default_factory=list)

    @property
    def core_url(self) -> str:
        return self.core.url

    async def client(self, program: str, *args: str) -> ClientRun:
        """Start a client scenario (``name.py`` with this Python, ``name.mjs`` with Node)."""
        path = CLIENTS / program
        if program.endswith(".mjs"):
            if NODE is None:
                pytest.skip("node is not installed")
            argv = [NODE, str(path), *args]
        else:
            argv = [sys.executable, str(path), *args]
        process = await asyncio.create_subprocess_exec(
            *argv, stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
            cwd=CLIENTS,
        )  # fmt: skip
        self.processes.append(process)
        return ClientRun(process, program)


class ClientRun:
    """A running client scenario: read its JSON lines, tell it to go on, wait for its end."""

    def __init__(self, process: asyncio.subprocess.Process, name: str) -> None:
        self.process = process
        self.name = name

    async def line(self, timeout_s: float = 20.0) -> dict[str, Any]:
        assert self.process.stdout is not None
        raw = await asyncio.wait_for(self.process.stdout.readline(), timeout_s)
        if not raw:
            error = await self.process.stderr.read() if self.process.stderr else b""
            raise AssertionError(f"{self.name} ended early:\n{error.decode(errors='replace')[-3000:]}")
        return json.loads(raw)  # type: ignore[no-any-return]

    async def expect(self, key: str, timeout_s: float = 20.0) -> dict[str, Any]:
        """Read lines until one has ``key``; returns that line."""
        while True:
            line = await self.line(timeout_s)
            if key in line:
                return line

    async def go_on(self) -> None:
        assert self.process.stdin is not None
        self.process.stdin.write(b"go\n")
        await self.process.stdin.drain()

    async def finish(self, timeout_s: float = 20.0) -> str:
        _, error = await asyncio.wait_for(self.process.communicate(), timeout_s)
        assert self.process.returncode == 0, f"{self.name} failed:\n{error.decode(errors='replace')[-3000:]}"
        return error.decode(errors="replace")


async def _start_bridge(token: str = "", **settings: object) -> AsyncIterator[Bridge]:
    sockets = {"rosbridge": listening_socket(), "foxglove": listening_socket()}
    rosbridge_port, foxglove_port = (sock.getsockname()[1] for sock in sockets.values())
    core = CoreProcess(
        endpoint_sockets=sockets, rosbridge_port=rosbridge_port, foxglove_port=foxglove_port, token=token, **settings
    )
    await core.start()
    drone = Drone(NodeSettings(core_url=core.url, port=0, token=token, ping_interval_s=1.0, ping_timeout_s=2.0))
    await drone.start()
    await wait_until(lambda: "/drone" in core.registry.nodes, what="the drone to register")
    bridge = Bridge(core, drone, f"ws://127.0.0.1:{rosbridge_port}", f"ws://127.0.0.1:{foxglove_port}", token)
    try:
        yield bridge
    finally:
        for process in bridge.processes:
            if process.returncode is None:
                process.kill()
                await process.wait()
        await drone.stop()
        await core.stop()


@pytest.fixture
async def bridge() -> AsyncIterator[Bridge]:
    async for running in _start_bridge():
        yield running


@pytest.fixture
async def locked_bridge() -> AsyncIterator[Bridge]:
    """The same, with a write token set (``SKYDECK_TOKEN``): ``secret``."""
    async for running in _start_bridge(token="secret"):
        yield running


@pytest.fixture
async def impatient_bridge() -> AsyncIterator[Bridge]:
    """The same, with a core that gives up soon: a call with no timeout of its own after 1 s (the
    gateway's default), a client that reads nothing for 1 s is stalled (the keepalive waits 60 s)."""
    async for running in _start_bridge(gateway_timeout_s=1.0, stall_timeout_s=1.0, ping_timeout_s=60.0):
        yield running


Connect = Callable[..., Awaitable[Any]]


class Tuned(Node):
    """A node with three parameters: the runtime serves ROS 2's parameter services for them and
    publishes /parameter_events (rcl_interfaces), as for every node."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("tuned", settings=settings)
        self.declare_parameter("max_speed", 2.5)
        self.declare_parameter("mode", "auto")
        self.declare_parameter("retries", 3)

    @property
    def values(self) -> dict[str, Any]:
        return {name: self.get_parameter(name).value for name in ("max_speed", "mode", "retries")}


@pytest.fixture
async def tuned(bridge: Bridge) -> AsyncIterator[Tuned]:
    """A Tuned node on the bridge's core."""
    node = Tuned(NodeSettings(core_url=bridge.core_url, port=0))
    await node.start()
    await wait_until(lambda: bridge.core.registry.service("/tuned/set_parameters") is not None, what="the node")
    yield node
    await node.stop()


class Stuck(Node):
    """A node whose one service, /stuck/wait, never answers."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("stuck", settings=settings)
        self.create_service(Trigger, "/stuck/wait", self.wait)

    async def wait(self, request: object) -> None:
        await asyncio.Event().wait()


@contextlib.asynccontextmanager
async def stuck_node(bridge: Bridge) -> AsyncIterator[Stuck]:
    """A Stuck node on the bridge's core, its service registered, for the block's length."""
    node = Stuck(NodeSettings(core_url=bridge.core_url, port=0))
    await node.start()
    try:
        await wait_until(lambda: bridge.core.registry.service("/stuck/wait") is not None, what="the service")
        yield node
    finally:
        await node.stop()
