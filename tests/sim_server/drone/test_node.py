"""The simulator as a node: its topics, inputs, reset and camera, driven over real sockets."""

from __future__ import annotations

import asyncio
import base64
import json

import httpx
from websockets.asyncio.client import connect

from services.runtime import Node
from services.runtime.edge.links import stream_url
from shared_models.geometry_msgs import Point, PoseArray, PoseStamped
from shared_models.mavros_msgs import PositionTarget
from shared_models.std_msgs import Header
from sim_server.drone.node import DroneSimNode
from sim_server.drone.settings import DroneSettings
from tests.conftest import wait_until


def _sim(seed: int = 1):
    return lambda settings: DroneSimNode(DroneSettings(seed=seed, boxes=8, speed=None), settings)


class Pilot(Node):
    """Streams a setpoint on sim time and records poses, like the control node."""

    def __init__(self, settings) -> None:
        super().__init__("pilot", settings=settings.model_copy(update={"use_sim_time": True}))
        self.target: Point | None = None
        self.poses: list[PoseStamped] = []
        self.boxes: list[PoseArray] = []
        self.setpoints = self.create_publisher(PositionTarget, "/drone/setpoint", 10)
        self.create_subscription(PoseStamped, "/drone/pose", self.poses.append, 1000)
        self.create_subscription(PoseArray, "/simulator/boxes", self.boxes.append, 10)
        self.create_timer(1 / 30, self.stream)

    def stream(self) -> None:
        if self.target is not None:
            self.setpoints.publish(PositionTarget(header=Header(frame_id="map"), position=self.target))


async def test_pose_boxes_and_clock_are_published_in_the_map_frame(start_node) -> None:
    sim = await start_node(_sim())
    pilot = await start_node(Pilot)
    await wait_until(lambda: pilot.poses and pilot.boxes, what="pose and boxes")
    assert pilot.poses[-1].header.frame_id == "map" and pilot.boxes[-1].header.frame_id == "map"
    assert len(pilot.boxes[-1].poses) == 8
    assert pilot.get_clock().now().nanoseconds > 0  # /clock drives the pilot's sim time
    seqs = [p.header.seq for p in pilot.poses[-5:]]
    assert seqs == sorted(seqs) and sim.world.time_s > 0


async def test_setpoint_stream_flies_the_drone_up(start_node) -> None:
    await start_node(_sim())
    pilot = await start_node(Pilot)
    pilot.target = Point(x=0.0, y=0.0, z=3.0)
    await wait_until(lambda: pilot.poses and pilot.poses[-1].pose.position.z > 2.8, timeout_s=30, what="3 m")


async def test_bad_setpoints_are_refused_and_the_sim_goes_on(start_node, caplog) -> None:
    sim = await start_node(_sim())
    async with connect(stream_url(sim.url, "/drone/setpoint")) as websocket:
        await websocket.send(json.dumps({"position": {"x": 500.0, "y": 0.0, "z": 3.0}}))
        await wait_until(lambda: "refused setpoint" in caplog.text, what="the warning")
    steps = sim.world.steps
    await wait_until(lambda: sim.world.steps > steps, what="the physics to keep stepping")
    assert sim.world.drone_pose()[0][2] < 0.2  # the drone never took the absurd target


async def test_reset_drops_new_boxes_and_boxes_are_latched(core, start_node) -> None:
    sim = await start_node(_sim())
    async with httpx.AsyncClient() as http:
        before = (await http.get(core.url + "/simulator/boxes")).json()
        reply = await http.post(core.url + "/simulator/reset")
    assert reply.status_code == 200 and reply.json()["success"] is True
    pilot = await start_node(Pilot)  # joins after the reset: the latched boxes come at once
    await wait_until(lambda: pilot.boxes, what="latched boxes")
    assert pilot.boxes[0].poses[0].position != PoseArray.model_validate(before).poses[0].position
    assert sim.resets == 1


async def test_camera_renders_only_while_watched(core, start_node) -> None:
    sim = await start_node(_sim())
    await asyncio.sleep(0.5)  # several camera periods pass with nobody watching
    assert sim.camera.compressed._endpoint.published_count == 0
    async with connect(stream_url(core.url, "/simulator/camera"), max_size=None) as websocket:
        frame = json.loads(await asyncio.wait_for(websocket.recv(), 10))
    assert frame["format"] == "jpeg"
    assert base64.b64decode(frame["data"])[:2] == b"\xff\xd8"
