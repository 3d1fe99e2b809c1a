"""How long grading takes: ``skydeck grade`` of the wall follower's assignment (its reference, the
shipped 50 s of sim time, one seed), as an instructor runs it, start to finish.

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

from services.bench.processes import BenchError
from services.bench.report import Result
from services.bench.runner import Family, Readings, Trial, median_of

__all__ = ["grading_family", "measure_grading"]

_ASSIGNMENT = Path("examples/assignments/wall_follower.yaml")
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


def grading_family(*, repetitions: int) -> Family:
    """The ``grading`` rows (see the module docstring)."""
    trial = Trial("grade", "skydeck grade wall_follower.yaml wall_follower, one seed", measure_grading)

    def summarise(readings: Readings) -> list[Result]:
        got = readings["grade"]
        run = Result("grade_run_s", median_of(got, "wall_s"), "s", target="< 30 s (one behaviour, one seed)",
                     samples=[r["wall_s"] for r in got],
                     detail={"sim_time_s": got[0]["sim_time_s"], "cpu_s_while_stepping": got[0]["cpu_s"]})  # fmt: skip
        run.met = (run.value or 0) < 30.0
        step = Result("grade_step_ms", median_of(got, "step_ms"), "ms a step", "CPU ms a step, every process",
                      median_of(got, "cpu_ms_per_step"), target="- (1/30 sim s a step, in lockstep)",
                      samples=[r["step_ms"] for r in got])  # fmt: skip
        rate = Result("grade_sim_rate", median_of(got, "sim_rate"), "x real time", target="- (while stepping)",
                      samples=[r["sim_rate"] for r in got])  # fmt: skip
        return [run, step, rate]

    return Family("grading", [trial], repetitions, summarise, rows=("grade_run_s", "grade_step_ms", "grade_sim_rate"))
