"""What grading writes, for one student and for a class.

One student: ``report.html`` and ``grade.json`` in their folder (:func:`save_report`). A class
(``skydeck grade ASSIGNMENT.yaml --class SUBMISSIONS``): each student graded in turn, in
``OUT/NAME/``, and ``OUT/gradebook.json``, the shape the class page reads::

    {"assignment": "wall_follower",
     "students": {"ada": {"score": 0.75, "passed": false,
                          "criteria": [{"name": "wall_follower.bumps", "passed": false, "figure": 2.0,
                                        "verdict": "FAIL wall_follower.bumps 2 <= 0"}, ...]}}}

A student whose files cannot be graded (none, a run that failed, a node that never joined) fails
with score 0 and each criterion's verdict saying why; the others are graded as usual.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from services.grading.assignment import Assignment, SeedKind
from services.grading.grade import GradeError, GradeReport, check_files, grade
from services.grading.report_html import render_report
from services.grading.students import Submission
from services.grading.verdicts import as_json, number, verdict_lines

__all__ = ["ClassResult", "StudentResult", "grade_class", "save_report"]


def save_report(report: GradeReport, out_dir: Path) -> dict[str, Any]:
    """Write ``report.html`` and ``grade.json`` into ``out_dir``; the JSON record."""
    html_path = out_dir / "report.html"
    html_path.write_text(render_report(report, out_dir), encoding="utf-8")
    record = as_json(report, html=str(html_path))
    (out_dir / "grade.json").write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
    return record


@dataclass
class StudentResult:
    """One student of a class: their report, or why they could not be graded."""

    student: str
    report: GradeReport | None
    problem: str = ""
    out_dir: Path | None = None

    @property
    def passed(self) -> bool:
        return self.report is not None and self.report.passed

    @property
    def score(self) -> float:
        if self.report is None:
            return 0.0
        return sum(criterion.passed for criterion in self.report.criteria) / len(self.report.criteria)

    def entry(self, assignment: Assignment) -> dict[str, Any]:
        """The student's line of the gradebook."""
        criteria: list[dict[str, Any]]
        if self.report is None:
            criteria = [
                {"name": use.name, "passed": False, "figure": None, "verdict": f"FAIL {use.name}: not graded: {self.problem}"}
                for use in assignment.criteria
            ]
        else:
            criteria = [
                {"name": result.name, "passed": result.passed, "figure": number(result.worst.value), "verdict": line}
                for result, line in zip(self.report.criteria, verdict_lines(self.report), strict=True)
            ]
        return {"score": round(self.score, 6), "passed": self.passed, "criteria": criteria}


@dataclass
class ClassResult:
    assignment: Assignment
    students: list[StudentResult]

    @property
    def passed(self) -> bool:
        return all(student.passed for student in self.students)

    def gradebook(self) -> dict[str, Any]:
        """``gradebook.json``'s record (see the module docstring)."""
        return {
            "assignment": self.assignment.assignment,
            "students": {student.student: student.entry(self.assignment) for student in self.students},
        }


async def grade_class(
    assignment: Assignment,
    submissions: list[Submission],
    *,
    seeds: list[int],
    seed_kind: SeedKind,
    out_dir: Path,
    on_student: Callable[[int, Submission], None] = lambda index, submission: None,
) -> ClassResult:
    """Grade each submission in turn into ``out_dir/NAME/``, then write ``out_dir/gradebook.json``.
    ``on_student(index, submission)`` is told before each (for progress)."""
    results = []
    for index, submission in enumerate(submissions):
        on_student(index, submission)
        results.append(await _grade_student(assignment, submission, seeds=seeds, seed_kind=seed_kind, out_dir=out_dir))
    result = ClassResult(assignment, results)
    (out_dir / "gradebook.json").write_text(json.dumps(result.gradebook(), indent=2) + "\n", encoding="utf-8")
    return result


async def _grade_student(
    assignment: Assignment, submission: Submission, *, seeds: list[int], seed_kind: SeedKind, out_dir: Path
) -> StudentResult:
    if submission.missing:
        return StudentResult(submission.student, None, submission.missing)
    own_dir = out_dir / submission.student
    files = [str(path) for path in submission.files]
    try:
        check_files(files)
        own_dir.mkdir(parents=True, exist_ok=True)
        report = await grade(assignment, files, student=submission.student, seeds=seeds, seed_kind=seed_kind, out_dir=own_dir)
    except GradeError as error:
        return StudentResult(submission.student, None, str(error), own_dir)
    except OSError as error:
        return StudentResult(submission.student, None, f"{own_dir}: {error.strerror or error}", own_dir)
    save_report(report, own_dir)
    return StudentResult(submission.student, report, out_dir=own_dir)
