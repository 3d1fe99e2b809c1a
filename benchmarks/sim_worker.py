"""Worker: one reading of :func:`sim_server.drone.speed.measure` (the world and a bare PyBullet loop).

    python -m benchmarks.sim_worker --boxes 8 --steps 4800     # RESULT {"bare_steps_per_s", ...}

In its own process so that it runs under the same conditions as the simulator node it is
compared with (one process, one core).
"""

from __future__ import annotations

import argparse

from benchmarks.sink import emit
from sim_server.drone.speed import measure


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--boxes", type=int, default=8)
    parser.add_argument("--steps", type=int, default=4800)
    args = parser.parse_args()
    reading = measure(seed=args.seed, boxes=args.boxes, steps=args.steps, repeats=1)
    emit("RESULT", {"bare_steps_per_s": reading.bare_steps_per_s, "world_steps_per_s": reading.world_steps_per_s})


if __name__ == "__main__":
    main()
