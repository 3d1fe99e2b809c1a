"""``skydeck grade``'s refusals: each one line and exit status 2, before any world is started."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.cli.main import main
from tests.services.grading.assignments import SOLUTIONS, shipped


def grade(capsys: pytest.CaptureFixture[str], *args: object) -> tuple[int, str]:
    status = main(["grade", *(str(a) for a in args)])
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


def test_class_needs_the_class_command(capsys: pytest.CaptureFixture[str]) -> None:
    status, err = grade(capsys, shipped("estop"), "estop", "--class")
    assert status == 2
    assert err == "skydeck: error: --class grades every student of a running class: it needs `skydeck class`, which is not here yet\n"


def test_an_out_folder_that_cannot_be_made(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    status, err = grade(capsys, shipped("estop"), "estop", "--out", blocker / "sub", "--json")
    assert status == 2 and f"--out {blocker / 'sub'}: cannot make the folder" in err


def test_usage_errors_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as raised:
        main(["grade", str(shipped("estop")), "estop", "--seeds", "secret"])
    assert raised.value.code == 2
