"""Worker: one reading of :func:`sim_server.robot.speed.measure` (the robot world with its laser,
and a bare PyBullet loop of the same scene casting the same rays).

    python -m benchmarks.robot_worker --steps 4800     # RESULT {"bare_steps_per_s", ...}

In its own process, as ``sim_worker`` is, so that it runs under the same conditions as the
simulator node it is compared with (one process, one core).
"""

from __future__ import annotations

import argparse
import dataclasses

from benchmarks.sink import emit
from sim_server.robot.speed import measure


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--robots", type=int, default=1)
    parser.add_argument("--steps", type=int, default=4800)
    args = parser.parse_args()
    reading = measure(seed=args.seed, robots=args.robots, steps=args.steps, repeats=1)
    emit("RESULT", dataclasses.asdict(reading))


if __name__ == "__main__":
    main()
