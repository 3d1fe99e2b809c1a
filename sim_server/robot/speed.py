"""How fast the robot world steps with its laser on, against a bare PyBullet loop of the same
scene casting the same rays.

Run ``python -m sim_server.robot.speed`` for a one-off reading; the benchmark suite calls
:func:`measure` (in ``services.bench.robot_worker``). Timings live here and in the benchmark,
never in pass/fail tests.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import dataclass

import pybullet as p

from sim_server.limits import PHYSICS_HZ
from sim_server.robot.limits import ODOM_EVERY_STEPS, SCAN_EVERY_STEPS
from sim_server.robot.world import RobotWorld, RobotWorldConfig

__all__ = ["RobotSpeedReading", "measure"]

_SETTLE_STEPS = PHYSICS_HZ


@dataclass(frozen=True, slots=True)
class RobotSpeedReading:
    """Physics steps per second of the world (driving, scanning at 5 Hz of sim time, reading its
    bumper and odometry at 30 Hz) and of a bare loop (stepSimulation, and the same 360-ray
    rayTestBatch every SCAN_EVERY_STEPS steps); milliseconds per scan in each."""

    world_steps_per_s: float
    bare_steps_per_s: float
    scan_ms: float
    bare_scan_ms: float

    @property
    def real_time_factor(self) -> float:
        """Sim seconds per wall-clock second of the world."""
        return self.world_steps_per_s / PHYSICS_HZ


def measure(*, seed: int = 1, robots: int = 1, steps: int = 4800, repeats: int = 3) -> RobotSpeedReading:
    """Best of ``repeats`` runs of ``steps`` steps for the world and for the bare loop."""
    best_world = best_bare = 0.0
    scan_ms = bare_scan_ms = float("inf")
    for _ in range(repeats):
        rate, scan = _world_rate(seed, robots, steps)
        best_world, scan_ms = max(best_world, rate), min(scan_ms, scan)
        rate, scan = _bare_rate(seed, robots, steps)
        best_bare, bare_scan_ms = max(best_bare, rate), min(bare_scan_ms, scan)
    return RobotSpeedReading(best_world, best_bare, scan_ms, bare_scan_ms)


def _settled(seed: int, robots: int) -> RobotWorld:
    world = RobotWorld(RobotWorldConfig(seed=seed, robots=robots))
    world.step(_SETTLE_STEPS)
    return world


def _world_rate(seed: int, robots: int, steps: int) -> tuple[float, float]:
    """The world as the simulator node drives it: commands, bumper, scans; no messages."""
    with _settled(seed, robots) as world:
        scan_s = 0.0
        scans = 0
        start = time.perf_counter()
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
        elapsed = time.perf_counter() - start
        return steps / elapsed, 1e3 * scan_s / max(scans, 1)


def _bare_rate(seed: int, robots: int, steps: int) -> tuple[float, float]:
    """stepSimulation, and every SCAN_EVERY_STEPS steps the very rays of each robot's scan, in
    one rayTestBatch each: the least any program simulating this scene could do."""
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
        start = time.perf_counter()
        for done in range(1, steps + 1):
            step_simulation(physicsClientId=client)
            if done % SCAN_EVERY_STEPS == 0:
                t0 = time.perf_counter()
                for start_points, end_points in rays:
                    ray_test(start_points, end_points, physicsClientId=client)
                scan_s += time.perf_counter() - t0
                scans += robots
        elapsed = time.perf_counter() - start
        return steps / elapsed, 1e3 * scan_s / max(scans, 1)


def main() -> None:
    """Print one reading."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, default=1)
    parser.add_argument("--steps", type=int, default=4800)
    args = parser.parse_args()
    reading = measure(robots=args.robots, steps=args.steps)
    print(
        f"robot world: {reading.real_time_factor:.1f}x real time, {reading.scan_ms:.2f} ms a scan; "
        f"bare loop: {reading.bare_steps_per_s / PHYSICS_HZ:.1f}x, {reading.bare_scan_ms:.2f} ms a scan"
    )


if __name__ == "__main__":
    main()
