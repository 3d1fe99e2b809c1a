"""Flying the simulated drone in tests: setpoint and cmd_vel streams, and what they did."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from sim_server.drone.limits import PHYSICS_HZ
from sim_server.drone.world import World

STEPS_PER_SETPOINT = PHYSICS_HZ // 30  # the control node's 30 Hz stream


@dataclass
class FlightLog:
    """What happened during one stretch of flight, sampled at 30 Hz."""

    positions: list[tuple[float, float, float]] = field(default_factory=list)
    max_tilt_deg: float = 0.0
    max_speed_xy: float = 0.0
    max_speed_z: float = 0.0

    @property
    def final(self) -> tuple[float, float, float]:
        return self.positions[-1]

    def record(self, world: World) -> None:
        (vx, vy, vz), _ = world.drone_velocity()
        self.positions.append(world.drone_pose()[0])
        self.max_tilt_deg = max(self.max_tilt_deg, world.tilt_deg())
        self.max_speed_xy = max(self.max_speed_xy, math.hypot(vx, vy))
        self.max_speed_z = max(self.max_speed_z, abs(vz))


def stream_setpoint(
    world: World, target: tuple[float, float, float], seconds: float, yaw: float = 0.0
) -> FlightLog:
    """Send ``target`` every 1/30 s of sim time for ``seconds``, recording the flight."""
    log = FlightLog()
    for _ in range(round(seconds * 30)):
        world.set_setpoint(*target, yaw=yaw)
        world.step(STEPS_PER_SETPOINT)
        log.record(world)
    return log


def stream_cmd_vel(
    world: World, velocity: tuple[float, float, float, float], seconds: float
) -> FlightLog:
    """Send ``velocity`` (vx, vy, vz, yaw_rate) every 1/30 s for ``seconds``."""
    log = FlightLog()
    for _ in range(round(seconds * 30)):
        world.set_cmd_vel(*velocity)
        world.step(STEPS_PER_SETPOINT)
        log.record(world)
    return log


def idle(world: World, seconds: float) -> FlightLog:
    """Step with no input for ``seconds``, recording."""
    log = FlightLog()
    for _ in range(round(seconds * 30)):
        world.step(STEPS_PER_SETPOINT)
        log.record(world)
    return log
