"""How fast the robot world steps with its laser on, against a bare PyBullet loop of the same
scene casting the same rays.

Run ``python -m sim_server.robot.speed`` for a one-off reading; the benchmark suite calls
:func:`measure` (in ``benchmarks.world_speed_worker``). Timings live here and in the benchmark,
never in pass/fail tests.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import pybullet as p

from sim_server.robot.bodies import SCAN_MASK
from sim_server.robot.limits import (
    CONTROL_EVERY_STEPS,
    MAX_CLASS_ROBOTS,
    ODOM_EVERY_STEPS,
    PHYSICS_HZ,
    SCAN_EVERY_STEPS,
)
from sim_server.robot.world import RobotWorld, RobotWorldConfig
from sim_server.speed_command import print_reading

__all__ = ["RobotSpeedReading", "measure"]

_SETTLE_STEPS = PHYSICS_HZ


@dataclass(frozen=True, slots=True)
class RobotSpeedReading:
    """Physics steps per second of the world (driving, scanning at 5 Hz of sim time, reading its
    bumper and odometry at 30 Hz) and of a bare loop (stepSimulation, and the same 360-ray
    rayTestBatch every SCAN_EVERY_STEPS steps); milliseconds per scan in each. The ``_cpu_s``
    rates are per second of this process's CPU time: what each would reach with a core to
    itself, whatever else the machine is doing."""

    world_steps_per_s: float
    bare_steps_per_s: float
    scan_ms: float
    bare_scan_ms: float
    world_steps_per_cpu_s: float
    bare_steps_per_cpu_s: float

    @property
    def real_time_factor(self) -> float:
        """Sim seconds per wall-clock second of the world."""
        return self.world_steps_per_s / PHYSICS_HZ

    def __str__(self) -> str:
        return (
            f"robot world: {self.real_time_factor:.1f}x real time, {self.scan_ms:.2f} ms a scan; "
            f"bare loop: {self.bare_steps_per_s / PHYSICS_HZ:.1f}x, {self.bare_scan_ms:.2f} ms a scan; "
            f"per CPU second: world {self.world_steps_per_cpu_s / PHYSICS_HZ:.1f}x, bare {self.bare_steps_per_cpu_s / PHYSICS_HZ:.1f}x"
        )


def measure(*, seed: int = 1, robots: int = 1, steps: int = 4800, repeats: int = 3) -> RobotSpeedReading:
    """Best of ``repeats`` runs of ``steps`` steps for the world and for the bare loop (taken in
    turns, so that a spell of load on the machine falls on both)."""
    runs = [(_world_rate(seed, robots, steps), _bare_rate(seed, robots, steps)) for _ in range(repeats)]
    world, bare = [w for w, _ in runs], [b for _, b in runs]
    return RobotSpeedReading(
        world_steps_per_s=max(r.steps_per_s for r in world),
        bare_steps_per_s=max(r.steps_per_s for r in bare),
        scan_ms=min(r.scan_ms for r in world),
        bare_scan_ms=min(r.scan_ms for r in bare),
        world_steps_per_cpu_s=max(r.steps_per_cpu_s for r in world),
        bare_steps_per_cpu_s=max(r.steps_per_cpu_s for r in bare),
    )


@dataclass(frozen=True, slots=True)
class _Run:
    steps_per_s: float
    steps_per_cpu_s: float
    scan_ms: float


class _Clocks:
    """Wall and CPU time of a run, started together."""

    def __init__(self) -> None:
        self.wall, self.cpu = time.perf_counter(), time.process_time()

    def run(self, steps: int, scan_s: float, scans: int) -> _Run:
        wall, cpu = time.perf_counter() - self.wall, time.process_time() - self.cpu
        return _Run(steps / wall, steps / max(cpu, 1e-9), 1e3 * scan_s / max(scans, 1))


def _settled(seed: int, robots: int) -> RobotWorld:
    world = RobotWorld(RobotWorldConfig(seed=seed, robots=robots))
    world.step(_SETTLE_STEPS)
    return world


def _world_rate(seed: int, robots: int, steps: int) -> _Run:
    """The world as the simulator node drives it: commands, bumper, scans; no messages."""
    with _settled(seed, robots) as world:
        scan_s = 0.0
        scans = 0
        clocks = _Clocks()
        for done in range(0, steps, ODOM_EVERY_STEPS):
            for robot in range(robots):
                world.set_cmd_vel(robot, 0.2, 0.4)  # an arc: the wheels and the laser at work
                world.odometry(robot)
                world.bump(robot)
            world.step(ODOM_EVERY_STEPS)
            if (done + ODOM_EVERY_STEPS) % SCAN_EVERY_STEPS == 0:
                t0 = time.perf_counter()
                for robot in range(robots):
                    world.scan(robot)
                scan_s += time.perf_counter() - t0
                scans += robots
        return clocks.run(steps, scan_s, scans)


def _bare_rate(seed: int, robots: int, steps: int) -> _Run:
    """stepSimulation, the person walking (its constraint moved each control tick, as the scene
    has it), and every SCAN_EVERY_STEPS steps the very rays of each robot's scan, in one
    rayTestBatch each with the laser's collision mask: the least any program simulating this
    scene (the same bodies, collision filters, time step and motion) could do. The robots stand,
    as they do in the node the benchmark compares with (nobody commands them)."""
    with _settled(seed, robots) as world:
        client = world.client
        laser = world._laser  # the same ray arrays the world casts
        rays = []
        for robot in range(robots):
            laser.scan(*world.robot_pose(robot))
            rays.append((laser._from.copy(), laser._to.copy()))
        step_simulation, ray_test = p.stepSimulation, p.rayTestBatch
        scan_s = 0.0
        scans = 0
        clocks = _Clocks()
        for done in range(1, steps + 1):
            step_simulation(physicsClientId=client)
            if done % CONTROL_EVERY_STEPS == 0:
                world.walk_person()
            if done % SCAN_EVERY_STEPS == 0:
                t0 = time.perf_counter()
                for start_points, end_points in rays:
                    ray_test(start_points, end_points, collisionFilterMask=SCAN_MASK, physicsClientId=client)
                scan_s += time.perf_counter() - t0
                scans += robots
        return clocks.run(steps, scan_s, scans)


def main() -> None:
    """Print one reading."""
    print_reading(__doc__ or "", measure, count="robots", default=1, span=(1, MAX_CLASS_ROBOTS))


if __name__ == "__main__":
    main()
