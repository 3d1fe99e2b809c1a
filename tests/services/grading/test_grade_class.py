"""``skydeck grade ASSIGNMENT --class SUBMISSIONS``, for real: a class of five on a roster, one
who passes, one whose node crashes, one whose node hangs, one with no file and one with no
folder; a folder that is not on the roster. Each is graded on their own: the one who passes
scores as they do graded alone, and the gradebook has the shape the class page reads."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.services.grading.assignments import SOLUTIONS, changed

pytestmark = [pytest.mark.e2e, pytest.mark.slow]


def skydeck_grade(*args: object) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "services.cli", "grade", *(str(a) for a in args)],
        capture_output=True, text=True, timeout=420,
    )  # fmt: skip


@pytest.mark.timeout(450)
def test_a_class_is_graded_student_by_student_into_one_gradebook(tmp_path: Path) -> None:
    assignment = changed("estop", tmp_path, seeds=[2], duration_s=20)
    submissions = tmp_path / "submissions"
    for student, solution in [("ada", "rospy_estop.py"), ("bob", "crashes.py"), ("cyd", "hangs.py"), ("zed", "rospy_estop.py")]:
        (submissions / student).mkdir(parents=True)
        shutil.copy(SOLUTIONS / solution, submissions / student / solution)
    (submissions / "dee").mkdir()
    (submissions / "dee" / "notes.txt").write_text("I ran out of time\n")
    roster = tmp_path / "roster.txt"
    roster.write_text("# estop, section B\nada\nbob\ncyd\ndee\neve  # joined late\n")
    out = tmp_path / "grades"

    done = skydeck_grade(assignment, "--class", submissions, "--roster", roster, "--out", out)

    assert done.returncode == 1, done.stdout + done.stderr
    lines = done.stdout.splitlines()
    assert [line.split()[:3] for line in lines[:5]] == [
        ["PASS", "ada", "1.00"], ["FAIL", "bob", "0.50"], ["FAIL", "cyd", "0.50"], ["FAIL", "dee", "0.00"], ["FAIL", "eve", "0.00"],
    ]  # fmt: skip
    assert lines[0].endswith(f"report: {out / 'ada' / 'report.html'}")
    assert f"not graded: no submission (no .py file in {submissions / 'dee'})" in lines[3]
    assert f"not graded: no submission (no folder {submissions / 'eve'})" in lines[4]
    assert lines[5] == f"gradebook: {out / 'gradebook.json'}"
    assert f"note: {submissions / 'zed'} is not on the roster: not graded" in done.stderr
    assert not (out / "zed").exists()

    book = json.loads((out / "gradebook.json").read_text())
    assert set(book) == {"assignment", "students"} and book["assignment"] == "estop"
    assert list(book["students"]) == ["ada", "bob", "cyd", "dee", "eve"]
    names = ["estop.travel_m", "estop.clearance_m", "estop.moved_after_stop_m", "estop.bumps"]
    for entry in book["students"].values():
        assert set(entry) == {"score", "passed", "criteria"}
        assert [c["name"] for c in entry["criteria"]] == names
        assert all(set(c) == {"name", "passed", "figure", "verdict"} for c in entry["criteria"])
    ada = book["students"]["ada"]
    assert ada["passed"] is True and ada["score"] == 1.0
    assert ada["criteria"][0]["verdict"].startswith("PASS estop.travel_m ")
    # bob's and cyd's robots never moved: the stop criteria hold, travel fails.
    for student in ("bob", "cyd"):
        assert [c["passed"] for c in book["students"][student]["criteria"]] == [False, True, False, True]
    assert book["students"]["eve"]["criteria"][0] == {
        "name": "estop.travel_m", "passed": False, "figure": None,
        "verdict": f"FAIL estop.travel_m: not graded: no submission (no folder {submissions / 'eve'})",
    }  # fmt: skip

    bob = json.loads((out / "bob" / "grade.json").read_text())["runs"][0]["nodes"][0]
    assert bob["exit_code"] == 1 and bob["hung"] is False
    cyd = json.loads((out / "cyd" / "grade.json").read_text())["runs"][0]
    assert cyd["nodes"][0]["hung"] is True and cyd["sim_time_s"] == pytest.approx(20.0, abs=0.05)
    assert cyd["lockstep"]["kept"] is False
    assert (out / "cyd" / "report.html").is_file()

    # Graded alone, ada scores exactly as in the class: the others did not disturb her run.
    alone = skydeck_grade(assignment, submissions / "ada" / "rospy_estop.py", "--student", "ada", "--out", tmp_path / "alone", "--json")
    assert alone.returncode == 0, alone.stdout + alone.stderr
    figures = [c["figure"] for c in json.loads(alone.stdout)["criteria"]]
    assert figures == [c["figure"] for c in ada["criteria"]]
