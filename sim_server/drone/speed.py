"""How fast the world steps, against a bare PyBullet loop of the same scene.

Run ``python -m sim_server.drone.speed`` for a one-off reading; the benchmark suite calls
:func:`measure`. Timings live here and in the benchmark, never in pass/fail tests.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import pybullet as p

from sim_server.drone.limits import MAX_BOXES, PHYSICS_HZ
from sim_server.drone.world import World, WorldConfig
from sim_server.speed_command import print_reading

__all__ = ["SpeedReading", "measure"]

_SETPOINT_EVERY_STEPS = 8  # a 30 Hz setpoint stream


@dataclass(frozen=True, slots=True)
class SpeedReading:
    """Physics steps per second of the world (flying) and of a bare stepSimulation loop."""

    world_steps_per_s: float
    bare_steps_per_s: float

    @property
    def real_time_factor(self) -> float:
        """Sim seconds per wall-clock second of the world."""
        return self.world_steps_per_s / PHYSICS_HZ

    @property
    def overhead(self) -> float:
        """Extra wall-clock time per step of the world relative to the bare loop (0.1 = 10%)."""
        return self.bare_steps_per_s / self.world_steps_per_s - 1.0

    def __str__(self) -> str:
        return (
            f"world: {self.world_steps_per_s:,.0f} steps/s "
            f"({self.real_time_factor:.1f}x real time); "
            f"bare stepSimulation loop: {self.bare_steps_per_s:,.0f} steps/s; "
            f"overhead {self.overhead:.0%}"
        )


def measure(*, seed: int = 1, boxes: int = 8, steps: int = 4800, repeats: int = 3) -> SpeedReading:
    """Time ``steps`` steps of a drone flying a square among settled boxes, and the same number
    of bare ``stepSimulation`` calls on the same scene; best of ``repeats`` for each."""
    world_best = bare_best = 0.0
    for _ in range(repeats):
        world_best = max(world_best, _world_rate(seed, boxes, steps))
        bare_best = max(bare_best, _bare_rate(seed, boxes, steps))
    return SpeedReading(world_best, bare_best)


def _settled_world(seed: int, boxes: int) -> World:
    world = World(WorldConfig(seed=seed, boxes=boxes))
    world.step(3 * PHYSICS_HZ)  # boxes land
    return world


def _world_rate(seed: int, boxes: int, steps: int) -> float:
    corners = ((0.0, 0.0, 3.0), (6.0, 0.0, 3.0), (6.0, 6.0, 4.0), (0.0, 6.0, 3.0))
    with _settled_world(seed, boxes) as world:
        start = time.perf_counter()
        for i in range(0, steps, _SETPOINT_EVERY_STEPS):
            world.set_setpoint(*corners[(i // (2 * PHYSICS_HZ)) % len(corners)], yaw=0.0)
            world.step(_SETPOINT_EVERY_STEPS)
        return steps / (time.perf_counter() - start)


def _bare_rate(seed: int, boxes: int, steps: int) -> float:
    with _settled_world(seed, boxes) as world:
        client = world.client
        step_simulation = p.stepSimulation
        start = time.perf_counter()
        for _ in range(steps):
            step_simulation(physicsClientId=client)
        return steps / (time.perf_counter() - start)


def main() -> None:
    """Print one reading."""
    print_reading(__doc__ or "", measure, count="boxes", default=8, span=(0, MAX_BOXES))


if __name__ == "__main__":
    main()
