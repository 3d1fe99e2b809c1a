"""The simulator node: the PyBullet world on topics and services (the seed's Gazebo + fake MAVROS).

    skydeck run sim --seed 1 --boxes 8 --speed max

Publishes (sim-time rates) ``/drone/pose`` 60 Hz, ``/clock`` with every pose, ``/simulator/boxes``
10 Hz (latched), ``/drone/state`` 5 Hz, ``/simulator/world`` (latched) once per build of the world
(at start and at every reset: a new random id each time), and ``/simulator/camera`` 5 Hz of wall
time only while someone subscribes. Follows ``/drone/setpoint`` and, when no setpoint stream is active,
``/drone/cmd_vel``. Serves ``/simulator/reset``. Bad input is refused with a warning and never
reaches the physics.
"""

from __future__ import annotations

import argparse
import asyncio
import math
import secrets
import time

from pydantic import Field, ValidationError, field_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

from services.runtime import Node, NodeSettings, spin
from services.runtime.parameters import InvalidParameterValueException
from services.runtime.settings import process_settings, settings_from_flags
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import Point, Pose, PoseArray, PoseStamped, Quaternion, Twist
from shared_models.mavros_msgs import PositionTarget, State
from shared_models.rcl_interfaces import IntegerRange, ParameterDescriptor
from shared_models.ros_workshop import SimWorld
from shared_models.sensor_msgs import CompressedImage
from shared_models.std_msgs import Header
from shared_models.std_srvs import Trigger, TriggerRequest, TriggerResponse
from sim_server.camera import render_jpeg
from sim_server.commands import InvalidCommand
from sim_server.limits import DEFAULT_BOXES, MAX_BOXES, PHYSICS_HZ
from sim_server.world import World, WorldConfig, draw_seed

__all__ = ["SimSettings", "SimulatorNode", "main"]

DEFAULT_PORT = 8001
POSE_EVERY_STEPS = PHYSICS_HZ // 60  # 60 Hz sim time
BOXES_EVERY_STEPS = PHYSICS_HZ // 10  # 10 Hz
STATE_EVERY_STEPS = PHYSICS_HZ // 5  # 5 Hz
CAMERA_PERIOD_S = 0.2  # 5 Hz wall time: rendering costs milliseconds, whatever the sim speed
# Falling further behind real time than this resets the pace instead of bursting to catch up.
_MAX_LAG_S = 0.25
_WARN_EVERY_S = 5.0


class SimSettings(BaseSettings):
    """The world's options: flags ``--seed/--boxes/--speed`` or ``SKYDECK_SIM_*`` variables."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_SIM_", extra="ignore")

    seed: int | None = Field(default=None, ge=0, le=2**32 - 1, description="None draws one")
    boxes: int = Field(default=DEFAULT_BOXES, ge=0, le=MAX_BOXES)
    speed: float | None = Field(
        default=1.0, description="times real time; None is as fast as possible"
    )

    @field_validator("speed", mode="before")
    @classmethod
    def _parse_speed(cls, value: object) -> object:
        if isinstance(value, str) and value.strip().lower() == "max":
            return None
        return value

    @field_validator("speed")
    @classmethod
    def _check_speed(cls, value: float | None) -> float | None:
        if value is not None and not (0 < value <= 1000 and math.isfinite(value)):
            raise ValueError("speed must be a number in (0, 1000] or 'max'")
        return value


class SimulatorNode(Node):
    """The world as a node; the physics loop runs in the node's event loop, in short chunks."""

    def __init__(
        self, sim: SimSettings | None = None, settings: NodeSettings | None = None
    ) -> None:
        super().__init__("sim", settings=settings or process_settings(NodeSettings, port=DEFAULT_PORT))
        self.sim = self._declare_world_parameters(sim or SimSettings())
        self.world = World(WorldConfig(seed=self.sim.seed, boxes=self.sim.boxes))
        self.pose_publisher = self.create_publisher(PoseStamped, "/drone/pose", 10)
        self.state_publisher = self.create_publisher(State, "/drone/state", 10)
        self.boxes_publisher = self.create_publisher(
            PoseArray, "/simulator/boxes", 10, latched=True
        )
        self.world_publisher = self.create_publisher(SimWorld, "/simulator/world", 1, latched=True)
        self.clock_publisher = self.create_publisher(Time, "/clock", 10)
        self.camera_publisher = self.create_publisher(CompressedImage, "/simulator/camera", 2)
        self.create_subscription(PositionTarget, "/drone/setpoint", self.on_setpoint, 10)
        self.create_subscription(Twist, "/drone/cmd_vel", self.on_cmd_vel, 10)
        self.create_service(Trigger, "/simulator/reset", self.on_reset)
        self.create_timer(CAMERA_PERIOD_S, self.publish_camera, wall_clock=True)
        self._last_warning = {"setpoint": -math.inf, "cmd_vel": -math.inf, "lag": -math.inf}
        self.resets = 0
        self.world_info = self._publish_world()
        speed = "max" if self.sim.speed is None else f"{self.sim.speed:g}x"
        self.get_logger().info(
            "world %s: seed %d, %d boxes, speed %s",
            self.world_info.id, self.world.seed, self.sim.boxes, speed,
        )

    def _declare_world_parameters(self, sim: SimSettings) -> SimSettings:
        """The world's options as read-only parameters (``skydeck param get /sim seed``); an
        override (``--ros-args -p seed:=5``) wins over the flag, as for any parameter."""
        seed = self.declare_parameter(
            "seed",
            draw_seed() if sim.seed is None else sim.seed,
            ParameterDescriptor(
                read_only=True,
                description="the world's random seed (drawn when not given): the same seed, the same world",
                integer_range=[IntegerRange(from_value=0, to_value=2**32 - 1)],
            ),
        ).value
        boxes = self.declare_parameter(
            "boxes",
            sim.boxes,
            ParameterDescriptor(
                read_only=True, description="number of boxes", integer_range=[IntegerRange(from_value=0, to_value=MAX_BOXES)]
            ),
        ).value
        speed = self.declare_parameter(
            "speed",
            "max" if sim.speed is None else sim.speed,
            ParameterDescriptor(read_only=True, dynamic_typing=True, description="times real time, or 'max'"),
        ).value
        try:
            return SimSettings(seed=seed, boxes=boxes, speed=speed)
        except ValidationError as error:
            raise InvalidParameterValueException(
                f"{self.get_name()}: parameter 'speed': {error.errors()[0]['msg']}"
            ) from None

    # -- inputs -------------------------------------------------------------------------------

    def on_setpoint(self, msg: PositionTarget) -> None:
        p = msg.position
        try:
            self.world.set_setpoint(p.x, p.y, p.z, yaw=msg.yaw)
        except InvalidCommand as error:
            self._warn("setpoint", f"refused setpoint: {error}")

    def on_cmd_vel(self, msg: Twist) -> None:
        try:
            self.world.set_cmd_vel(msg.linear.x, msg.linear.y, msg.linear.z, msg.angular.z)
        except InvalidCommand as error:
            self._warn("cmd_vel", f"refused cmd_vel: {error}")

    def on_reset(self, request: TriggerRequest) -> TriggerResponse:
        self.world.reset()
        self.resets += 1
        self.world_info = self._publish_world()
        self._publish_boxes(self._header())
        self.get_logger().info("world %s: reset %d, %d new boxes", self.world_info.id, self.resets, self.sim.boxes)
        return TriggerResponse(
            success=True,
            message=(
                f"world reset: drone at the start, {self.sim.boxes} new boxes dropped"
                f" (world {self.world_info.id})"
            ),
        )

    def _warn(self, kind: str, text: str) -> None:
        # A bad stream would log at its own rate: one line per kind every few seconds is enough.
        now = time.monotonic()
        if now - self._last_warning[kind] >= _WARN_EVERY_S:
            self._last_warning[kind] = now
            self.get_logger().warning("%s", text)

    # -- outputs ------------------------------------------------------------------------------

    def _header(self) -> Header:
        return Header(stamp=Time.from_seconds(self.world.time_s), frame_id="map")

    def _publish_world(self) -> SimWorld:
        """Announce a new build of the world: a random id that no other build has (progress
        saved for one build, the AI's, must never be taken for another, even of the same seed)."""
        info = SimWorld(
            header=self._header(),
            id=secrets.token_hex(8),
            seed=self.world.seed,
            build=self.resets,
            boxes=self.sim.boxes,
        )
        self.world_publisher.publish(info)
        return info

    def _publish_tick(self, steps: int) -> None:
        """Publish what is due after the physics reached ``steps``."""
        header = self._header()
        (x, y, z), (qx, qy, qz, qw) = self.world.drone_pose()
        self.pose_publisher.publish(
            PoseStamped(
                header=header,
                pose=Pose(
                    position=Point(x=x, y=y, z=z), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw)
                ),
            )
        )
        self.clock_publisher.publish(header.stamp.model_copy())
        if steps % BOXES_EVERY_STEPS == 0:
            self._publish_boxes(header.model_copy())
        if steps % STATE_EVERY_STEPS == 0:
            state = self.world.drone_state()
            self.state_publisher.publish(
                State(
                    header=header.model_copy(),
                    connected=True,
                    armed=state.armed,
                    guided=state.mode.value == "OFFBOARD",
                    manual_input=False,
                    mode=state.mode.value,
                    system_status=4 if state.armed else 3,  # MAV_STATE_ACTIVE / STANDBY
                )
            )

    def _publish_boxes(self, header: Header) -> None:
        poses = [
            Pose(position=Point(x=x, y=y, z=z), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw))
            for (x, y, z), (qx, qy, qz, qw) in self.world.boxes_poses()
        ]
        self.boxes_publisher.publish(PoseArray(header=header, poses=poses))

    def publish_camera(self) -> None:
        if self.camera_publisher.get_subscription_count() == 0:
            return  # rendering costs milliseconds: only while someone watches
        self.camera_publisher.publish(
            CompressedImage(header=self._header(), format="jpeg", data=render_jpeg(self.world))
        )

    # -- the physics loop ---------------------------------------------------------------------

    async def start(self) -> None:
        await super().start()
        self._physics = asyncio.get_running_loop().create_task(self._run_physics())

    async def stop(self) -> None:
        physics = getattr(self, "_physics", None)
        if physics is not None:
            physics.cancel()
            await asyncio.gather(physics, return_exceptions=True)
        await super().stop()
        self.world.close()

    async def _run_physics(self) -> None:
        """Step in chunks of one pose period, publish, and keep pace with the wall clock."""
        world = self.world
        speed = self.sim.speed
        sim_origin_s = world.time_s
        wall_origin_s = time.monotonic()
        self._publish_tick(world.steps)
        while True:
            world.step(POSE_EVERY_STEPS - world.steps % POSE_EVERY_STEPS)
            self._publish_tick(world.steps)
            if speed is None:
                await asyncio.sleep(0)  # as fast as possible, but let sockets and callbacks run
                continue
            ahead_s = wall_origin_s + (world.time_s - sim_origin_s) / speed - time.monotonic()
            if ahead_s > 0:
                await asyncio.sleep(ahead_s)
            else:
                if -ahead_s > _MAX_LAG_S:
                    self._warn(
                        "lag", f"physics is {-ahead_s:.2f} s behind real time at speed {speed:g}x"
                    )
                    sim_origin_s, wall_origin_s = world.time_s, time.monotonic()
                await asyncio.sleep(0)


def main(argv: list[str] | None = None) -> int:
    """``skydeck run sim [--seed N] [--boxes K] [--speed F|max]``."""
    parser = argparse.ArgumentParser(
        prog="skydeck run sim", description="The PyBullet drone world."
    )
    parser.add_argument("--seed", help="random seed; the same seed gives the same world")
    parser.add_argument("--boxes", help=f"number of boxes, 0-{MAX_BOXES} (default {DEFAULT_BOXES})")
    parser.add_argument("--speed", help="times real time, or 'max' (default 1)")
    spin(SimulatorNode(settings_from_flags(parser, SimSettings, argv)))
    return 0
