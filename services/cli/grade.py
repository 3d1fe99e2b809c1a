"""``skydeck grade ASSIGNMENT.yaml FILES...``: run a student's nodes in fresh seeded worlds and
score what they did (docs/grading.md).

    skydeck grade examples/assignments/wall_follower.yaml my_wall_follower.py --student ada

Prints a verdict per criterion (``PASS wall_follower.band_fraction 0.93 >= 0.80``), the
recordings and the report; writes ``grade.json`` and ``report.html`` to ``--out``. Exit status
0 when every criterion passes, 1 when one fails, 2 when grading could not be done (a bad
assignment file, a file that is not a node, a world that would not run).

    skydeck grade examples/assignments/wall_follower.yaml --class submissions [--roster roster.txt]

grades every student's ``submissions/NAME/*.py`` in turn (a line each), writes each one's
report to ``OUT/NAME/`` and the class's ``OUT/gradebook.json``. Exit status 0 when every student
passed, 1 when one did not, 2 when the class could not be graded (a bad roster or folder).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
from pathlib import Path

from services.cli.settings import cli_settings

__all__ = ["add_parser"]

EXIT_PASSED, EXIT_FAILED, EXIT_ERROR = 0, 1, 2


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "grade",
        help="run a student's nodes in seeded worlds and score them against an assignment",
        description=(
            "Runs FILES (rospy/rclpy/SDK node files, or built-in nodes) as `skydeck run` does, in a "
            "fresh world per seed at full speed, in lockstep (the same files and seed give the same "
            "score), records each run and scores the assignment's criteria. Exit status: 0 every "
            "criterion passed, 1 one failed, 2 grading could not be done."
        ),
    )
    p.add_argument("assignment", metavar="ASSIGNMENT.yaml", help="the assignment file (examples/assignments/)")
    p.add_argument("files", nargs="*", metavar="FILE", help="the student's node files (.py), or built-in node names")
    p.add_argument("--student", default="student", help="the student's name, for the report and the folder (default: student)")
    p.add_argument(
        "--seeds", choices=("visible", "hidden"), default="visible",
        help="visible: the assignment's own seeds (default); hidden: the instructor's, from SKYDECK_GRADE_SECRET",
    )  # fmt: skip
    p.add_argument(
        "--out", type=Path, metavar="DIR",
        help="where runs and reports go (default: grades/ASSIGNMENT/STUDENT; with --class grades/ASSIGNMENT)",
    )  # fmt: skip
    p.add_argument("--json", action="store_true", help="print the gradebook's JSON instead of the verdict lines")
    p.add_argument(
        "--class", dest="submissions", type=Path, metavar="SUBMISSIONS",
        help="grade every student's SUBMISSIONS/NAME/*.py instead of FILEs; writes OUT/gradebook.json",
    )  # fmt: skip
    p.add_argument(
        "--roster", type=Path, metavar="FILE",
        help="with --class: the students to grade, one name a line ('#' comments); default: every folder",
    )  # fmt: skip
    p.set_defaults(func=_grade)


def _error(message: str) -> int:
    print(f"skydeck: error: {message}", file=sys.stderr)
    return EXIT_ERROR


def _grade(args: argparse.Namespace) -> int:
    from services.grading.assignment import AssignmentError, load_assignment
    from services.grading.grade import GradeError, check_files, grade
    from services.grading.gradebook import save_report
    from services.grading.verdicts import node_note, verdict_lines

    if args.submissions is not None:
        return _grade_class(args)
    if args.roster is not None:
        return _error("--roster goes with --class SUBMISSIONS (it says whose folders are graded)")
    from services.grading.students import RosterError, check_student_name

    try:
        check_student_name(args.student)  # the class's rule: graded alone as in a class
    except RosterError as error:
        return _error(f"--student {args.student!r}: {error}")
    try:
        assignment = load_assignment(Path(args.assignment))
        check_files(args.files)
        seeds = assignment.seeds_for(args.seeds, secret=cli_settings().grade_secret)
    except (AssignmentError, GradeError) as error:
        return _error(str(error))
    out_dir: Path = args.out or Path("grades") / assignment.assignment / args.student
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        return _error(f"--out {out_dir}: cannot make the folder: {error.strerror or error}")
    print(
        f"grading {', '.join(args.files)} against {assignment.assignment}: {len(seeds)} {args.seeds} "
        f"seed{'s' if len(seeds) > 1 else ''}, {assignment.duration_s:g} s of sim time each",
        file=sys.stderr,
    )
    try:
        report = asyncio.run(
            grade(assignment, args.files, student=args.student, seeds=seeds, seed_kind=args.seeds, out_dir=out_dir)
        )
    except GradeError as error:
        return _error(str(error))
    record = save_report(report, out_dir)
    if args.json:
        print(json.dumps(record, indent=2))
    else:
        for line in verdict_lines(report):
            print(line)
        for run in report.runs:
            print(f"recording (seed {run.seed}): {run.result.bag}")
            for node in run.student_nodes:
                note = node_note(node)
                if note is not None:
                    print(f"note: {note} (seed {run.seed}): see {node.log}")
            if run.result.lockstep_lost:
                print(f"note: seed {run.seed} was not kept in lockstep ({run.result.lockstep_reason})")
        print(f"report: {record['report']}")
    return EXIT_PASSED if report.passed else EXIT_FAILED


def _grade_class(args: argparse.Namespace) -> int:
    """``--class SUBMISSIONS``: every student's files, a line each, then the gradebook."""
    from services.grading.assignment import AssignmentError, load_assignment
    from services.grading.gradebook import grade_class
    from services.grading.students import RosterError, Submission, find_submissions, read_roster

    if args.files:
        return _error("--class grades the files in SUBMISSIONS/NAME/: give no FILE as well")
    if args.student != "student":
        return _error("--class names each student by their folder: give no --student as well")
    try:
        assignment = load_assignment(Path(args.assignment))
        roster = read_roster(args.roster) if args.roster is not None else None
        found = find_submissions(args.submissions, roster)
        seeds = assignment.seeds_for(args.seeds, secret=cli_settings().grade_secret)
    except (AssignmentError, RosterError) as error:
        return _error(str(error))
    out_dir: Path = args.out or Path("grades") / assignment.assignment
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        return _error(f"--out {out_dir}: cannot make the folder: {error.strerror or error}")
    for folder in found.not_on_roster:
        print(f"note: {folder} is not on the roster: not graded", file=sys.stderr)
    count = len(found.submissions)

    def progress(index: int, submission: Submission) -> None:
        print(f"grading {submission.student} ({index + 1}/{count}) ...", file=sys.stderr)

    print(
        f"grading {count} student{'s' if count > 1 else ''} against {assignment.assignment}: {len(seeds)} "
        f"{args.seeds} seed{'s' if len(seeds) > 1 else ''}, {assignment.duration_s:g} s of sim time each",
        file=sys.stderr,
    )
    result = asyncio.run(
        grade_class(assignment, found.submissions, seeds=seeds, seed_kind=args.seeds, out_dir=out_dir, on_student=progress)
    )
    book = result.gradebook()
    if args.json:
        print(json.dumps(book, indent=2))
    else:
        for student in result.students:
            entry = book["students"][student.student]
            failed = [criterion["name"] for criterion in entry["criteria"] if not criterion["passed"]]
            line = f"{'PASS' if student.passed else 'FAIL'} {student.student} {entry['score']:.2f}"
            if student.problem:
                line += f"  not graded: {student.problem}"
            elif failed:
                line += f"  failed: {', '.join(failed)}"
            if student.report is not None and student.out_dir is not None:
                line += f"  report: {student.out_dir / 'report.html'}"
            print(line)
        print(f"gradebook: {out_dir / 'gradebook.json'}")
    return EXIT_PASSED if result.passed else EXIT_FAILED
