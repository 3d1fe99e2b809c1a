"""A grade in words and in JSON: a line per criterion, and the gradebook's record.

    PASS wall_follower.band_fraction 0.93 >= 0.80
    FAIL wall_follower.bumps 2 <= 0  [seed 1: 0, seed 2: 2]

With several seeds the figure shown is the worst seed's (the one that failed, or came nearest
to failing), then every seed's.
"""

from __future__ import annotations

import math
from typing import Any

from services.grading.grade import GradeReport
from services.grading.run import NodeOutcome

__all__ = ["as_json", "format_value", "node_note", "number", "verdict_lines"]


def format_value(value: float) -> str:
    """A figure or a threshold as the verdict line shows it: whole numbers as such, else two
    decimals; ``inf``; ``n/a`` for a figure that could not be measured."""
    if math.isnan(value):
        return "n/a"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    if value == int(value) and abs(value) < 1e9:
        return f"{value:.0f}"
    return f"{value:.2f}"


def verdict_lines(report: GradeReport) -> list[str]:
    """One line per criterion: PASS or FAIL, its name, the figure, the threshold."""
    lines = []
    for criterion in report.criteria:
        use, worst = criterion.use, criterion.worst
        line = (
            f"{'PASS' if criterion.passed else 'FAIL'} {criterion.name} "
            f"{format_value(worst.value)} {use.comparison} {format_value(use.threshold)}"
        )
        if len(criterion.figures) > 1:
            line += "  [" + ", ".join(f"seed {f.seed}: {format_value(f.value)}" for f in criterion.figures) + "]"
        lines.append(line)
    return lines


def node_note(node: NodeOutcome) -> str | None:
    """What befell a node before the run ended, in words (None: it ran to the end); the log follows."""
    if node.hung:
        return f"{node.label} stayed busy for a whole settle (a loop that never ends?) and was stopped"
    if node.exit_code is not None:
        return f"{node.label} exited with status {node.exit_code} before the run ended"
    return None


def number(value: float) -> float | None:
    """JSON has no infinity or NaN: those are null (the detail says why)."""
    return round(value, 6) if math.isfinite(value) else None


def as_json(report: GradeReport, *, html: str = "") -> dict[str, Any]:
    """The gradebook's record of ``report`` (``grade.json``)."""
    passed = sum(criterion.passed for criterion in report.criteria)
    return {
        "assignment": report.assignment.assignment,
        "student": report.student,
        "files": report.files,
        "seeds": {"kind": report.seed_kind, "list": [run.seed for run in report.runs]},
        "passed": report.passed,
        "score": round(passed / len(report.criteria), 6),
        "criteria": [
            {
                "name": criterion.name,
                "unit": criterion.use.spec.unit,
                "comparison": criterion.use.comparison,
                "threshold": criterion.use.threshold,
                "passed": criterion.passed,
                "figure": number(criterion.worst.value),
                "seeds": [
                    {"seed": f.seed, "figure": number(f.value), "passed": f.passed, "detail": f.detail}
                    for f in criterion.figures
                ],
            }
            for criterion in report.criteria
        ],
        "runs": [
            {
                "seed": run.seed,
                "mcap": str(run.result.bag),
                "sim_time_s": round(run.result.sim_time_s, 6),
                "wall_time_s": round(run.result.wall_time_s, 3),
                "steps": run.result.steps,
                "stepping": {
                    "wall_s": round(run.result.stepping_wall_s, 3),
                    "cpu_s": {name: round(cpu, 3) for name, cpu in run.result.stepping_cpu_s.items()},
                },
                "lockstep": {"kept": run.result.lockstep_lost == 0, "lost": run.result.lockstep_lost, "reason": run.result.lockstep_reason},
                "nodes": [
                    {"node": node.label, "student": node.student, "exit_code": node.exit_code, "hung": node.hung, "log": str(node.log)}
                    for node in run.result.nodes
                ],
            }
            for run in report.runs
        ],
        "report": html,
    }
