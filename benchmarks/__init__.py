"""Skydeck's benchmark suite: the project and its references side by side, in one run.

    from benchmarks import run_bench
    outcome = run_bench(quick=True, out=Path("bench.json"))
    print(outcome.table)

One module per family: :mod:`~benchmarks.topics` (throughput and latency, Skydeck vs a bare
``websockets`` pair vs zenoh), :mod:`~benchmarks.fanout`, :mod:`~benchmarks.services`
(round trips direct, through the gateway, bare FastAPI), :mod:`~benchmarks.sim`,
:mod:`~benchmarks.mission`, :mod:`~benchmarks.startup`. :mod:`~benchmarks.runner`
repeats and interleaves, :mod:`~benchmarks.suite` sets the parameters, :mod:`~benchmarks.families`
lists the families, whose rows and targets :mod:`~benchmarks.topic_families`,
:mod:`~benchmarks.world_families` and :mod:`~benchmarks.system_families` make;
:mod:`~benchmarks.report` and :mod:`~benchmarks.plots` write the results. Workers run
as ``python -m benchmarks.<worker>`` in their own processes.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from benchmarks.report import Result, format_table, machine_info, write_json

__all__ = ["Outcome", "Result", "run_bench"]


@dataclass
class Outcome:
    """What a run produced: the rows, the printed table, the plot files, and how many errors."""

    results: list[Result]
    table: str
    plots: list[Path] = field(default_factory=list)

    @property
    def errors(self) -> int:
        return sum(1 for r in self.results if r.error)


def run_bench(
    *, quick: bool = False, out: Path | None = None, plots: Path | None = None, only: set[str] | None = None
) -> Outcome:
    """Run the suite (or the families of the rows in ``only``) and write the JSON and plots.

    Raises ValueError for a name in ``only`` that is neither a family nor a row.
    """
    from benchmarks.families import families as families_of
    from benchmarks.plots import write_plots
    from benchmarks.runner import run_families
    from benchmarks.suite import FULL, QUICK, Suite

    suite = Suite(QUICK if quick else FULL, plots=plots is not None)
    try:
        every = families_of(suite)
        if only:
            known = {f.name for f in every} | {row for f in every for row in f.rows}
            unknown = sorted(only - known)
            if unknown:
                raise ValueError(f"--only: unknown {', '.join(unknown)}; known: {', '.join(sorted(known))}")
        families = families_of(suite, only)
        machine = machine_info()
        started = time.monotonic()
        results = run_families(families)
        elapsed_s = time.monotonic() - started
    finally:
        suite.close()
    written = write_plots(suite.plot_data, plots) if plots is not None else []
    if out is not None:
        run = {"quick": quick, "only": sorted(only) if only else None, "elapsed_s": round(elapsed_s, 1),
               "settings": vars(suite.settings) | {}, "plots": [str(p) for p in written]}  # fmt: skip
        write_json(out, results, machine, run)
    return Outcome(results, format_table(results), written)
