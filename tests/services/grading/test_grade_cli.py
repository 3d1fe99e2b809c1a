"""``skydeck grade``'s refusals: each one line and exit status 2, before any world is started."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.cli.main import main
from tests.services.grading.assignments import SOLUTIONS, shipped


def grade(capsys: pytest.CaptureFixture[str], *args: object) -> tuple[int, str]:
    args = tuple(str(a) for a in args)
    status = main(["grade", *args])
    err = capsys.readouterr().err
    return status, err


def test_a_malformed_assignment(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text(shipped("estop").read_text().replace("max: 0\n", "max: zero\n"))
    status, err = grade(capsys, bad, "estop")
    assert status == 2
    assert err == f"skydeck: error: {bad}: criteria.3.max: Input should be a valid number, unable to parse string as a number\n"


def test_an_assignment_that_is_not_there(capsys: pytest.CaptureFixture[str]) -> None:
    assert grade(capsys, "nope.yaml", "estop") == (2, "skydeck: error: nope.yaml: no such assignment file\n")


@pytest.mark.parametrize(
    ("target", "says"),
    [
        ("missing.py", "missing.py: no such file"),
        ("notes.txt", "notes.txt: not a node: give a .py file or a built-in node"),
        ("sim", "sim: not a node"),
    ],
)
def test_files_that_are_not_nodes(target: str, says: str, capsys: pytest.CaptureFixture[str]) -> None:
    status, err = grade(capsys, shipped("estop"), target)
    assert status == 2
    assert err.startswith(f"skydeck: error: {says}") and err.count("\n") == 1


def test_hidden_seeds_without_the_secret(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SKYDECK_GRADE_SECRET", raising=False)
    status, err = grade(capsys, shipped("estop"), SOLUTIONS / "rospy_estop.py", "--seeds", "hidden")
    assert status == 2
    assert "SKYDECK_GRADE_SECRET" in err and err.count("\n") == 1


def test_a_student_name_that_cannot_name_a_folder(capsys: pytest.CaptureFixture[str]) -> None:
    status, err = grade(capsys, shipped("estop"), "estop", "--student", "../x")
    assert status == 2 and "--student '../x'" in err


def test_no_files_at_all(capsys: pytest.CaptureFixture[str]) -> None:
    status, err = grade(capsys, shipped("estop"))
    assert (status, err) == (2, "skydeck: error: give the student's node files (FILE.py) or built-in nodes to grade\n")


@pytest.mark.parametrize(
    ("extra", "says"),
    [
        (["estop"], "--class grades the files in SUBMISSIONS/NAME/: give no FILE as well"),
        (["--student", "ada"], "--class names each student by their folder: give no --student as well"),
    ],
)
def test_class_mode_takes_no_files_or_student(
    extra: list[str], says: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, err = grade(capsys, shipped("estop"), *extra, "--class", tmp_path)
    assert (status, err) == (2, f"skydeck: error: {says}\n")


def test_a_roster_needs_class_mode(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, err = grade(capsys, shipped("estop"), "estop", "--roster", tmp_path / "roster.txt")
    assert (status, err) == (2, "skydeck: error: --roster goes with --class SUBMISSIONS (it says whose folders are graded)\n")


def test_class_mode_refuses_a_bad_roster_or_folder_in_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "subs" / "ada").mkdir(parents=True)
    roster = tmp_path / "roster.txt"
    roster.write_text("ada\nbob  # late joiner\nAda\n")
    status, err = grade(capsys, shipped("estop"), "--class", tmp_path / "subs", "--roster", roster, "--out", tmp_path / "out")
    assert status == 2
    assert err == (
        f"skydeck: error: {roster}:3: Ada is a student already (line 1): each student once\n"
    )
    status, err = grade(capsys, shipped("estop"), "--class", tmp_path / "nowhere", "--out", tmp_path / "out")
    assert (status, err.count("\n")) == (2, 1) and "nowhere: no such folder" in err
    (tmp_path / "subs" / "Grace Hopper").mkdir()
    status, err = grade(capsys, shipped("estop"), "--class", tmp_path / "subs", "--out", tmp_path / "out")
    assert (status, err.count("\n")) == (2, 1)
    assert "Grace Hopper: 'Grace Hopper' cannot be a student's name" in err
    assert not (tmp_path / "out").exists()  # refused before anything was made


def test_an_out_folder_that_cannot_be_made(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    status, err = grade(capsys, shipped("estop"), "estop", "--out", blocker / "sub", "--json")
    assert status == 2 and f"--out {blocker / 'sub'}: cannot make the folder" in err


def test_usage_errors_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as raised:
        main(["grade", str(shipped("estop")), "estop", "--seeds", "secret"])
    assert raised.value.code == 2
