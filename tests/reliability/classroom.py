"""A class on one core, for the fences' tests: two students' tokens (alice, bob) and the
instructor's, a process token for the instructor's own nodes, and the nodes a class runs.

    /sim              the world (the process token): /clock, each student's /NAME/scan (latched)
                      and /NAME/cmd_vel (it drives by them), /NAME/ping, /simulator/reset
    /skydeck_launch   the launch (the process token): /skydeck_launch/kill_node, which records
                      whom it was asked to stop (and stops nobody)
    /NAME/driver      each student's own node (their token), a parameter ``gain``

The core serves rosbridge and Foxglove on free ports. Everything is real: uvicorn, sockets, the
SDK's nodes; the clients are the tests' (httpx, websockets, roslibpy, @foxglove/ws-protocol).
"""

from __future__ import annotations

import asyncio
import textwrap
from collections.abc import AsyncIterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx

from services.access import make_class_tokens, write_tokens
from services.runtime import Node, NodeSettings
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Twist
from shared_models.skydeck_launch import KillNode, KillNodeRequest, KillNodeResponse
from shared_models.std_msgs import String
from shared_models.std_srvs import Trigger, TriggerResponse
from tests.conftest import CoreProcess, listening_socket, wait_until

STUDENTS = ("alice", "bob")

# A student's program as they write it (rclpy, unchanged): drives ahead on {topic} at 20 Hz.
WALL_FOLLOWER = textwrap.dedent(
    """
    import rclpy
    from rclpy.node import Node
    from geometry_msgs.msg import Twist


    class WallFollower(Node):
        def __init__(self):
            super().__init__("wall_follower")
            self.cmd_vel = self.create_publisher(Twist, "{topic}", 10)
            self.create_timer(0.05, self.tick)
            self.get_logger().info("driving " + self.get_namespace())

        def tick(self):
            msg = Twist()
            msg.linear.x = 0.3
            self.cmd_vel.publish(msg)


    rclpy.init()
    rclpy.spin(WallFollower())
    """
)
PROCESS_TOKEN = "the-instructors-processes-token"


class World(Node):
    """The class's world, as the simulator offers it (see the module docstring)."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("sim", settings=settings)
        self.commands: dict[str, list[Twist]] = {student: [] for student in STUDENTS}
        self.resets = 0
        self.ticks = 0
        self.clock_publisher = self.create_publisher(Time, "/clock", 10)
        for student in STUDENTS:
            scan = self.create_publisher(String, f"/{student}/scan", 1, latched=True)
            scan.publish(String(data=f"{student}'s scan"))
            self.create_subscription(Twist, f"/{student}/cmd_vel", self.commands[student].append, 1000)
            self.create_service(Trigger, f"/{student}/ping", lambda request, s=student: TriggerResponse(success=True, message=f"{s}'s pong"))
        self.create_service(Trigger, "/simulator/reset", self._reset)
        self.create_timer(0.02, self._tick)

    def _reset(self, request: object) -> TriggerResponse:
        self.resets += 1
        return TriggerResponse(success=True, message="the world starts again")

    def _tick(self) -> None:
        self.ticks += 1
        self.clock_publisher.publish(Time(sec=self.ticks // 50, nanosec=(self.ticks % 50) * 20_000_000))


class Launch(Node):
    """``/skydeck_launch``: asked to stop nodes, it records which (and stops nobody)."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("skydeck_launch", settings=settings)
        self.asked: list[str] = []
        self.create_service(KillNode, "/skydeck_launch/kill_node", self._kill)

    def _kill(self, request: KillNodeRequest) -> KillNodeResponse:
        self.asked.append(request.node)
        return KillNodeResponse(success=True, message=f"stopped {request.node}", reason=KillNodeResponse.KILLED)


class Driver(Node):
    """A student's own node: ``/NAME/driver`` with a parameter ``gain``."""

    def __init__(self, student: str, settings: NodeSettings) -> None:
        super().__init__("driver", namespace=f"/{student}", settings=settings)
        self.declare_parameter("gain", 1.0)


@dataclass
class Classroom:
    core: CoreProcess
    tokens: dict[str, str]
    tokens_file: Path
    world: World
    launch: Launch
    drivers: dict[str, Driver]
    rosbridge_url: str
    foxglove_url: str
    nodes: list[Node] = field(default_factory=list)

    @property
    def url(self) -> str:
        return self.core.url

    def token(self, subject: str) -> str:
        """The token of ``subject`` (a student, ``instructor``, ``process``; ``nobody``: none)."""
        if subject == "process":
            return PROCESS_TOKEN
        return self.tokens.get(subject, "")

    def headers(self, subject: str) -> dict[str, str]:
        token = self.token(subject)
        return {"Authorization": f"Bearer {token}"} if token else {}

    def http(self, subject: str) -> httpx.AsyncClient:
        return httpx.AsyncClient(base_url=self.url, headers=self.headers(subject), timeout=10)

    def node_settings(self, subject: str, **more: Any) -> NodeSettings:
        return NodeSettings(
            core_url=self.url, port=0, token=self.token(subject), ping_interval_s=1.0, ping_timeout_s=2.0, **more
        )


async def open_classroom(folder: Path, **settings: Any) -> AsyncIterator[Classroom]:
    """A running class (see the module docstring); ``settings`` go to the core."""
    tokens = make_class_tokens(STUDENTS)
    tokens_file = folder / "class-tokens.csv"
    write_tokens(tokens_file, tokens)
    sockets = {"rosbridge": listening_socket(), "foxglove": listening_socket()}
    rosbridge_port, foxglove_port = (sock.getsockname()[1] for sock in sockets.values())
    core = CoreProcess(
        endpoint_sockets=sockets,
        rosbridge_port=rosbridge_port,
        foxglove_port=foxglove_port,
        class_tokens=tokens_file,
        token=PROCESS_TOKEN,
        recordings_dir=folder / "recordings",
        **settings,
    )
    await core.start()
    room = Classroom(
        core, tokens, tokens_file, None, None, {}, f"ws://127.0.0.1:{rosbridge_port}", f"ws://127.0.0.1:{foxglove_port}"
    )  # type: ignore[arg-type]
    try:
        room.world = World(room.node_settings("process"))
        room.launch = Launch(room.node_settings("process"))
        room.drivers = {student: Driver(student, room.node_settings(student)) for student in STUDENTS}
        room.nodes = [room.world, room.launch, *room.drivers.values()]
        await asyncio.gather(*(node.start() for node in room.nodes))
        names = {"/sim", "/skydeck_launch", "/alice/driver", "/bob/driver"}
        await wait_until(lambda: names <= core.registry.nodes.keys(), what="the class's nodes to register")
        yield room
    finally:
        await asyncio.gather(*(node.stop() for node in room.nodes), return_exceptions=True)
        await core.stop()
