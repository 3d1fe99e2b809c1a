"""Grading one student: run their node files on each seed of an assignment and score the runs.

    report = await grade(assignment, ["wall_follower.py"], student="ada", seeds=[1, 2],
                         out_dir=Path("grades/wall_follower/ada"))
    report.passed                   # every criterion met on every seed
    report.criteria[0].worst        # the seed where it came closest to failing (or failed)

This is the unit a class is graded in: ``skydeck grade`` calls it once, a class would call it
once per student (their files, their name), each in a folder of its own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from services.builtin_nodes import BUILTIN_NODES
from services.grading.assignment import Assignment, CriterionUse, SeedKind
from services.grading.criteria.base import Mark
from services.grading.run import NodeCommand, NodeOutcome, RunPlan, RunResult, run_world
from services.grading.tracks import Tracks, read_tracks
from shared_models.errors import SkydeckError

__all__ = ["CriterionResult", "GradeError", "GradeReport", "SeedFigure", "SeedRun", "check_files", "grade"]


class GradeError(SkydeckError):
    """Grading could not be done as asked (files that are not nodes, a world that failed)."""


@dataclass(frozen=True)
class SeedFigure:
    """One criterion on one seed."""

    seed: int
    value: float
    detail: str
    passed: bool
    marks: tuple[Mark, ...] = ()


@dataclass
class CriterionResult:
    """One criterion over every seed: it passes when it passes on each."""

    use: CriterionUse
    figures: list[SeedFigure]

    @property
    def name(self) -> str:
        return self.use.name

    @property
    def passed(self) -> bool:
        return all(figure.passed for figure in self.figures)

    @property
    def worst(self) -> SeedFigure:
        """The failing seed furthest from the threshold, else the passing one nearest it."""

        def margin(figure: SeedFigure) -> float:
            if not math.isfinite(figure.value):
                return -math.inf
            return figure.value - self.use.threshold if self.use.min is not None else self.use.threshold - figure.value

        return min(self.figures, key=margin)


@dataclass
class SeedRun:
    """One seed's run: where it was recorded and how it went."""

    seed: int
    out_dir: Path
    result: RunResult
    tracks: Tracks

    @property
    def student_nodes(self) -> list[NodeOutcome]:
        return [node for node in self.result.nodes if node.student]


@dataclass
class GradeReport:
    assignment: Assignment
    student: str
    files: list[str]
    seed_kind: SeedKind
    runs: list[SeedRun] = field(default_factory=list)
    criteria: list[CriterionResult] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return all(criterion.passed for criterion in self.criteria)


def check_files(files: list[str]) -> None:
    """Each is a node ``skydeck run`` can start: a built-in's name or an existing ``.py`` file."""
    if not files:
        raise GradeError("give the student's node files (FILE.py) or built-in nodes to grade")
    for name in files:
        if name in BUILTIN_NODES and name != "sim":
            continue
        path = Path(name)
        if path.suffix != ".py":
            raise GradeError(f"{name}: not a node: give a .py file or a built-in node ({', '.join(n for n in BUILTIN_NODES if n != 'sim')})")
        if not path.is_file():
            raise GradeError(f"{name}: no such file")


def _plan(assignment: Assignment, files: list[str], seed: int, out_dir: Path) -> RunPlan:
    nodes = [NodeCommand(name, student=False) for name in assignment.nodes]
    nodes += [NodeCommand(name, dict(assignment.parameters)) for name in files]
    return RunPlan(
        world=assignment.world,
        seed=seed,
        options=dict(assignment.options),
        duration_s=assignment.duration_s,
        nodes=nodes,
        out_dir=out_dir,
    )


async def grade(
    assignment: Assignment, files: list[str], *, student: str, seeds: list[int], seed_kind: SeedKind, out_dir: Path
) -> GradeReport:
    """Run ``files`` on each seed in ``out_dir/seed-N/`` and score every criterion of
    ``assignment``; GradeError if a run could not be made (not if the student's node failed:
    that is in the report, and its criteria fail)."""
    from services.grading.run import RunFailed

    check_files(files)
    report = GradeReport(assignment, student, list(files), seed_kind)
    for seed in seeds:
        seed_dir = out_dir / f"seed-{seed}"
        try:
            result = await run_world(_plan(assignment, files, seed, seed_dir))
        except RunFailed as error:
            raise GradeError(f"seed {seed}: the run failed: {error}") from None
        report.runs.append(SeedRun(seed, seed_dir, result, read_tracks(result.bag)))
    for use in assignment.criteria:
        options = use.options()
        figures = []
        for run in report.runs:
            figure = use.spec.run(run.tracks, options)
            figures.append(SeedFigure(run.seed, figure.value, figure.detail, use.passes(figure.value), figure.marks))
        report.criteria.append(CriterionResult(use, figures))
    return report
