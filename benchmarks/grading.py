"""How long grading takes (the ``grading`` family, :func:`benchmarks.world_families.grading`):
``skydeck grade`` of the wall follower's assignment (its reference, the shipped 50 s of sim time,
one seed), as an instructor runs it, start to finish.

Rows: ``grade_run_s`` (the command's wall time: the world's processes started, the run stepped
in lockstep, recorded, scored, reported), ``grade_step_ms`` (wall time of one lockstep step, a
thirtieth of a sim second, against the CPU time every process spent on it) and
``grade_sim_rate`` (sim seconds per wall second while stepping).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import yaml

from benchmarks.processes import BenchError

__all__ = ["measure_grading"]

_ASSIGNMENT = Path(__file__).resolve().parents[1] / "examples" / "assignments" / "wall_follower.yaml"
_TIMEOUT_S = 600.0


def measure_grading(assignment: Path = _ASSIGNMENT) -> dict[str, Any]:
    """One ``skydeck grade`` of ``assignment``'s reference on its first visible seed."""
    data = yaml.safe_load(assignment.read_text())
    data["seeds"]["visible"] = data["seeds"]["visible"][:1]
    with tempfile.TemporaryDirectory(prefix="skydeck-bench-grade-") as folder:
        copy = Path(folder) / assignment.name
        copy.write_text(yaml.safe_dump(data))
        out = Path(folder) / "out"
        started = time.monotonic()
        done = subprocess.run(
            [sys.executable, "-m", "services.cli", "grade", str(copy), data["reference"], "--out", str(out)],
            capture_output=True, text=True, timeout=_TIMEOUT_S,
        )  # fmt: skip
        wall_s = time.monotonic() - started
        if done.returncode != 0:
            raise BenchError(f"skydeck grade exited {done.returncode}: {(done.stdout + done.stderr)[-400:]}")
        run = json.loads((out / "grade.json").read_text())["runs"][0]
    stepping = run["stepping"]
    steps = max(run["steps"], 1)
    return {
        "wall_s": wall_s,
        "step_ms": 1000.0 * stepping["wall_s"] / steps,
        "cpu_ms_per_step": 1000.0 * sum(stepping["cpu_s"].values()) / steps,
        "sim_rate": run["sim_time_s"] / max(stepping["wall_s"], 1e-9),
        "sim_time_s": run["sim_time_s"],
        "cpu_s": stepping["cpu_s"],
    }
