"""Worker: one reading of a world's speed, the world and a bare PyBullet loop of the same scene
(:func:`sim_server.drone.speed.measure`; :func:`sim_server.robot.speed.measure`, whose bare loop
casts the same rays as the robots' lasers).

    python -m benchmarks.world_speed_worker drone --count 8 --steps 4800   # RESULT {"bare_steps_per_s", ...}
    python -m benchmarks.world_speed_worker robot --steps 4800

In its own process so that it runs under the same conditions as the simulator node it is
compared with (one process, one core).
"""

from __future__ import annotations

import argparse
import dataclasses

from benchmarks.sink import emit


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("world", choices=("drone", "robot"))
    parser.add_argument("--count", type=int, help="boxes in the drone world (8), robots in the robot world (1)")
    parser.add_argument("--steps", type=int, default=4800)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if args.world == "drone":
        from sim_server.drone.speed import measure as measure_drone

        emit("RESULT", dataclasses.asdict(measure_drone(seed=args.seed, boxes=args.count or 8, steps=args.steps, repeats=1)))
    else:
        from sim_server.robot.speed import measure as measure_robot

        emit("RESULT", dataclasses.asdict(measure_robot(seed=args.seed, robots=args.count or 1, steps=args.steps, repeats=1)))


if __name__ == "__main__":
    main()
