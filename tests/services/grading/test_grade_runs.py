"""Grading for real: worlds, nodes and recordings. The shipped references pass, a wrong solution
fails on the right criterion, the same run graded twice scores the same, to the last bit."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from services.grading.assignment import hidden_seed, load_assignment
from services.grading.grade import GradeReport, grade
from services.grading.tracks import read_tracks
from services.grading.verdicts import verdict_lines
from tests.services.grading.assignments import SOLUTIONS, changed, shipped

pytestmark = [pytest.mark.e2e, pytest.mark.slow]

ASSIGNMENTS = ["drive_square", "estop", "wall_follower", "person_follower", "obstacle_avoider", "fsm", "drone_mission"]


def skydeck_grade(*args: object, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "services.cli", "grade", *(str(a) for a in args)],
        capture_output=True, text=True, timeout=240, cwd=cwd,
    )  # fmt: skip


async def grade_once(path: Path, files: list[str], out_dir: Path, seed: int | None = None) -> GradeReport:
    assignment = load_assignment(path)
    seeds = [seed if seed is not None else assignment.seeds.visible[0]]
    return await grade(assignment, files, student="test", seeds=seeds, seed_kind="visible", out_dir=out_dir)


@pytest.mark.timeout(240)
@pytest.mark.parametrize("name", ASSIGNMENTS)
async def test_the_reference_passes_its_assignment(name: str, tmp_path: Path) -> None:
    assignment = load_assignment(shipped(name))
    report = await grade_once(shipped(name), [assignment.reference], tmp_path)
    lines = verdict_lines(report)
    assert report.passed, "\n".join(lines)
    assert [line.split()[1] for line in lines] == [use.name for use in assignment.criteria]
    run = report.runs[0]
    assert run.result.lockstep_lost == 0
    assert run.result.sim_time_s == pytest.approx(assignment.duration_s, abs=0.05)
    assert run.result.bag.is_file()


@pytest.mark.timeout(240)
def test_a_wall_follower_driving_into_the_wall_fails_on_bumps_and_the_band(tmp_path: Path) -> None:
    path = changed("wall_follower", tmp_path, seeds=[1], duration_s=25)
    done = skydeck_grade(path, SOLUTIONS / "into_the_wall.py", "--student", "ada", "--out", tmp_path / "out")
    assert done.returncode == 1, done.stdout + done.stderr
    verdicts = {line.split()[1]: line.split()[0] for line in done.stdout.splitlines() if line.startswith(("PASS", "FAIL"))}
    assert verdicts == {
        "wall_follower.time_to_wall_s": "FAIL",
        "wall_follower.band_fraction": "FAIL",
        "wall_follower.followed_m": "FAIL",
        "wall_follower.bumps": "FAIL",
    }
    record = json.loads((tmp_path / "out" / "grade.json").read_text())
    assert record["student"] == "ada" and record["passed"] is False and record["score"] == 0.0
    bumps = next(c for c in record["criteria"] if c["name"] == "wall_follower.bumps")
    assert bumps["figure"] >= 1 and "_front)" in bumps["seeds"][0]["detail"]  # it hit head on
    assert f"recording (seed 1): {tmp_path / 'out' / 'seed-1' / 'run.mcap'}" in done.stdout


@pytest.mark.timeout(240)
async def test_the_same_files_and_seed_score_the_same_twice(tmp_path: Path) -> None:
    """A rospy node (a Rate loop, a subscriber thread) graded twice: the same figures, exactly,
    and the same world truth at every recorded instant."""
    path = changed("estop", tmp_path, duration_s=20)
    files = [str(SOLUTIONS / "rospy_estop.py")]
    first = await grade_once(path, files, tmp_path / "first", seed=2)
    second = await grade_once(path, files, tmp_path / "second", seed=2)
    assert first.passed, "\n".join(verdict_lines(first))
    assert [(c.name, [f.value for f in c.figures]) for c in first.criteria] == [
        (c.name, [f.value for f in c.figures]) for c in second.criteria
    ]
    assert read_tracks(first.runs[0].result.bag).robot == read_tracks(second.runs[0].result.bag).robot


@pytest.mark.timeout(240)
def test_a_student_file_given_as_a_file_passes(tmp_path: Path) -> None:
    """The workshop's own first behaviour, examples/robot/my_estop.py, run as a file, with the
    command line's text and files."""
    path = changed("estop", tmp_path, seeds=[1], duration_s=20)
    done = skydeck_grade(path, "examples/robot/my_estop.py", "--out", tmp_path / "out")
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.splitlines()[:4] == [
        line for line in done.stdout.splitlines() if line.startswith("PASS")
    ]
    assert (tmp_path / "out" / "report.html").is_file()
    assert done.stdout.splitlines()[-1] == f"report: {tmp_path / 'out' / 'report.html'}"


@pytest.mark.timeout(240)
def test_a_node_that_crashes_fails_and_says_so(tmp_path: Path) -> None:
    path = changed("estop", tmp_path, seeds=[1], duration_s=2)
    done = skydeck_grade(path, SOLUTIONS / "crashes.py", "--out", tmp_path / "out", "--json")
    assert done.returncode == 1, done.stdout + done.stderr
    record = json.loads(done.stdout)
    assert record["passed"] is False
    assert [c["passed"] for c in record["criteria"]] == [False, True, False, True]  # it never moved
    node = record["runs"][0]["nodes"][0]
    assert node["node"] == "crashes.py" and node["exit_code"] == 1
    assert "this student's node is broken" in Path(node["log"]).read_text()


@pytest.mark.timeout(240)
def test_the_reference_passes_a_hidden_seed_only_the_secret_gives(tmp_path: Path) -> None:
    path = changed("estop", tmp_path, duration_s=20)
    path.write_text(path.read_text().replace("hidden: 2", "hidden: 1"))
    env = {**os.environ, "SKYDECK_GRADE_SECRET": "a secret kept out of the repository"}
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "grade", str(path), "estop", "--seeds", "hidden", "--out", str(tmp_path / "out"), "--json"],
        capture_output=True, text=True, timeout=200, env=env,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    record = json.loads(done.stdout)
    seed = hidden_seed("a secret kept out of the repository", "estop", 0)
    assert record["seeds"] == {"kind": "hidden", "list": [seed]}
    assert record["passed"] is True and [run["seed"] for run in record["runs"]] == [seed]
    assert seed not in load_assignment(path).seeds.visible


@pytest.mark.timeout(240)
def test_a_safety_stop_that_never_stops_fails_on_the_clearance_and_the_bumps(tmp_path: Path) -> None:
    """The wrong node graded against another assignment: it travels (that passes) and comes to
    rest against the wall (it moves no more: that passes too), but with no gap and a bump."""
    path = changed("estop", tmp_path, seeds=[1], duration_s=25)
    done = skydeck_grade(path, SOLUTIONS / "into_the_wall.py", "--out", tmp_path / "out")
    assert done.returncode == 1, done.stdout + done.stderr
    verdicts = {line.split()[1]: line.split()[0] for line in done.stdout.splitlines() if line.startswith(("PASS", "FAIL"))}
    assert verdicts == {
        "estop.travel_m": "PASS",
        "estop.clearance_m": "FAIL",
        "estop.moved_after_stop_m": "PASS",
        "estop.bumps": "FAIL",
    }
