"""The simulated world: a quadrotor and falling boxes in headless PyBullet, stepped at 240 Hz.

Example::

    from sim_server.drone.world import World, WorldConfig

    world = World(WorldConfig(seed=1, boxes=8))
    world.set_setpoint(0.0, 0.0, 3.0, yaw=0.0)   # re-send at ~30 Hz, or the failsafe holds
    world.step(240)                              # one second of sim time
    position, orientation = world.drone_pose()
    world.reset()                                # back to the start, a new set of boxes
    world.close()

The drone is flown only by forces: four rotor thrusts at the arm ends, the rotors' drag torque,
and linear air drag, all computed by the on-board controller from the latest input. Each world
owns its own PyBullet client, so several can live in one process. Not thread-safe: call a world
from one thread at a time.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

import pybullet as p

from sim_server.bullet import BulletWorld
from sim_server.checks import InvalidCommand
from sim_server.drone.airframe import IRIS, Airframe
from sim_server.drone.boxes import sample_boxes
from sim_server.drone.commands import CommandArbiter, ControlMode
from sim_server.drone.controller import CascadedController
from sim_server.drone.limits import (
    DEFAULT_BOXES,
    GRAVITY_M_S2,
    MAX_BOXES,
    ON_GROUND_Z_M,
    PHYSICS_DT_S,
    PHYSICS_HZ,
    START_XY_M,
)
from sim_server.drone.scene import BOX_COLOURS, create_box, create_drone, create_ground
from sim_server.geometry import Pose, Vector3, yaw_of
from sim_server.settings import draw_seed

__all__ = ["DroneState", "InvalidCommand", "Pose", "World", "WorldConfig"]


@dataclass(frozen=True, slots=True)
class WorldConfig:
    """How to build a world. The same seed gives the same boxes and, for the same inputs,
    the same trajectory; ``seed=None`` draws one (read it back from ``World.seed``)."""

    seed: int | None = None
    boxes: int = DEFAULT_BOXES
    airframe: Airframe = field(default=IRIS)
    position_loop_divider: int = 4
    """Run the position and velocity loops every this many physics steps (4: 60 Hz); the
    attitude and rate loops run every step, as on a real flight controller."""

    def __post_init__(self) -> None:
        if not 0 <= self.boxes <= MAX_BOXES:
            raise ValueError(f"boxes={self.boxes} is outside [0, {MAX_BOXES}]")
        if self.position_loop_divider < 1:
            raise ValueError(f"position_loop_divider={self.position_loop_divider} must be >= 1")


@dataclass(frozen=True, slots=True)
class DroneState:
    """What the flight controller reports (the simulator's MAVROS State)."""

    mode: ControlMode
    armed: bool
    """Motors running."""
    landed: bool
    """On the ground with the motors stopped."""
    on_ground: bool
    """Altitude at or below ON_GROUND_Z_M."""


class World(BulletWorld):
    """A headless PyBullet world with one quadrotor and ``config.boxes`` boxes."""

    PHYSICS_HZ = PHYSICS_HZ
    GRAVITY_M_S2 = GRAVITY_M_S2  # the controller's hover thrust assumes the same

    def __init__(self, config: WorldConfig | None = None) -> None:
        super().__init__()
        self.config = config or WorldConfig()
        seed = self.config.seed
        self.seed: int = draw_seed() if seed is None else seed
        self._rng = random.Random(self.seed)
        airframe = self.config.airframe
        self._start: Vector3 = (START_XY_M[0], START_XY_M[1], airframe.rest_z_m)
        self._controller = CascadedController(airframe)
        self._arbiter = CommandArbiter(*self._start, yaw=0.0)
        self._drag = airframe.linear_drag_n_s_m
        self._rotors = airframe.rotor_positions_m
        self._drone = -1
        self._boxes: list[int] = []
        self._build()

    # -- lifecycle -----------------------------------------------------------------------------

    def reset(self) -> None:
        """Put the drone back on the ground at the start, clear its controller and inputs, and
        drop the next set of boxes of this seed's sequence. The clock keeps running."""
        self._check_open()
        self._build()

    # -- inputs --------------------------------------------------------------------------------

    def set_setpoint(self, x: float, y: float, z: float, yaw: float = 0.0) -> None:
        """Fly to (x, y, z) facing ``yaw`` (rad). Re-send at ~30 Hz: after STREAM_TIMEOUT_S of
        sim time without one the drone returns to where it was when the last one arrived and
        holds there. Raises InvalidCommand."""
        self._check_open()
        (px, py, pz), orientation = self.drone_pose()
        self._arbiter.set_setpoint(
            self.time_s, x, y, z, yaw, drone_pose=(px, py, pz, yaw_of(orientation))
        )

    def set_cmd_vel(
        self, vx: float, vy: float, vz: float, yaw_rate: float = 0.0
    ) -> tuple[float, float, float, float]:
        """Fly at this world-frame velocity (m/s) and yaw rate (rad/s) while no setpoint stream
        is active; counts as zero after STREAM_TIMEOUT_S. Returns the command as clamped to the
        speed limits. Raises InvalidCommand for non-finite values."""
        self._check_open()
        return self._arbiter.set_cmd_vel(self.time_s, vx, vy, vz, yaw_rate)

    # -- stepping ------------------------------------------------------------------------------

    def step(self, n: int = 1) -> None:
        """Advance the world by ``n`` physics steps of 1/240 s."""
        self._check_steps(n)
        # Locals: this loop is the simulator's hot path.
        client = self._client
        drone = self._drone
        controller = self._controller
        arbiter = self._arbiter
        divider = self.config.position_loop_divider
        outer_dt = divider * PHYSICS_DT_S
        drag = self._drag
        r0, r1, r2, r3 = self._rotors
        get_pose = p.getBasePositionAndOrientation
        get_velocity = p.getBaseVelocity
        apply_force = p.applyExternalForce
        apply_torque = p.applyExternalTorque
        step_simulation = p.stepSimulation
        link_frame = p.LINK_FRAME
        world_frame = p.WORLD_FRAME
        steps = self._steps
        for _ in range(n):
            position, (qx, qy, qz, qw) = get_pose(drone, physicsClientId=client)
            (vx, vy, vz), (wx, wy, wz) = get_velocity(drone, physicsClientId=client)
            if steps % divider == 0:
                px, py, pz = position
                yaw = yaw_of((qx, qy, qz, qw))
                ref = arbiter.update(steps * PHYSICS_DT_S, outer_dt, px, py, pz, yaw)
                controller.update_position(ref, px, py, pz, vx, vy, vz, outer_dt)
            if not controller.idle:
                t0, t1, t2, t3, yaw_torque = controller.update_attitude(qx, qy, qz, qw, wx, wy, wz)
                apply_force(drone, -1, (0.0, 0.0, t0), r0, link_frame, physicsClientId=client)
                apply_force(drone, -1, (0.0, 0.0, t1), r1, link_frame, physicsClientId=client)
                apply_force(drone, -1, (0.0, 0.0, t2), r2, link_frame, physicsClientId=client)
                apply_force(drone, -1, (0.0, 0.0, t3), r3, link_frame, physicsClientId=client)
                apply_torque(drone, -1, (0.0, 0.0, yaw_torque), link_frame, physicsClientId=client)
                apply_force(
                    drone,
                    -1,
                    (-drag * vx, -drag * vy, -drag * vz),
                    position,
                    world_frame,
                    physicsClientId=client,
                )
            step_simulation(physicsClientId=client)
            steps += 1
            self._steps = steps

    # -- read-out ------------------------------------------------------------------------------

    def drone_pose(self) -> Pose:
        """Drone position (x, y, z) in m and orientation quaternion (x, y, z, w)."""
        self._check_open()
        return p.getBasePositionAndOrientation(self._drone, physicsClientId=self._client)

    def drone_velocity(self) -> tuple[Vector3, Vector3]:
        """Drone linear (m/s) and angular (rad/s) velocity, world frame."""
        self._check_open()
        return p.getBaseVelocity(self._drone, physicsClientId=self._client)

    def boxes_poses(self) -> list[Pose]:
        """Each box's centre (x, y, z) and orientation (x, y, z, w), in spawn order."""
        self._check_open()
        return [
            p.getBasePositionAndOrientation(box, physicsClientId=self._client)
            for box in self._boxes
        ]

    @property
    def on_ground(self) -> bool:
        """Whether the drone is at or below ON_GROUND_Z_M (the take-off check)."""
        return self.drone_pose()[0][2] <= ON_GROUND_Z_M

    def tilt_deg(self) -> float:
        """Angle between the drone's body z axis and the vertical, in degrees."""
        qx, qy, _, _ = self.drone_pose()[1]
        cos_tilt = 1.0 - 2.0 * (qx * qx + qy * qy)
        return math.degrees(math.acos(max(-1.0, min(1.0, cos_tilt))))

    def drone_state(self) -> DroneState:
        """Flight mode, armed and landed flags."""
        on_ground = self.on_ground
        armed = not self._controller.idle
        return DroneState(
            mode=self._arbiter.mode,
            armed=armed,
            landed=on_ground and not armed,
            on_ground=on_ground,
        )

    # -- internals -----------------------------------------------------------------------------

    def _build(self) -> None:
        # A fresh world whose random sequence has moved on.
        client = self._fresh_simulation()
        create_ground(client)
        self._drone = create_drone(client, self.config.airframe, self._start)
        spawns = sample_boxes(self._rng, self.config.boxes)
        self._boxes = [
            create_box(client, spawn, BOX_COLOURS[i % len(BOX_COLOURS)])
            for i, spawn in enumerate(spawns)
        ]
        self._controller.reset()
        self._arbiter.reset(*self._start, yaw=0.0)

