"""Who class mode grades: students' names, the roster file, the submissions folder."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.grading.students import RosterError, check_student_name, find_submissions, read_roster


@pytest.mark.parametrize("name", ["ada", "Grace_Hopper", "r2d2", "a" * 63])
def test_names_a_namespace_can_have(name: str) -> None:
    assert check_student_name(name) == name


@pytest.mark.parametrize(
    ("name", "says"),
    [
        ("2pac", "cannot be a student's name: a letter, then"),
        ("_ada", "cannot be a student's name"),
        ("ada lovelace", "cannot be a student's name"),
        ("ada/bob", "cannot be a student's name"),
        ("a" * 64, "at most 63"),
        ("", "cannot be a student's name"),
        ("instructor", "'instructor' is the instructor's line"),
    ],
)
def test_names_refused(name: str, says: str) -> None:
    with pytest.raises(RosterError, match=None) as raised:
        check_student_name(name)
    assert says in str(raised.value) and "\n" not in str(raised.value)


def test_a_roster_file_one_name_a_line_with_comments(tmp_path: Path) -> None:
    roster = tmp_path / "roster.txt"
    roster.write_text("# CS 123, spring\nada\n\n  bob   # joined late\ncyd\n")
    assert read_roster(roster) == ["ada", "bob", "cyd"]


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("ada\nbob\nada\n", "roster.txt:3: ada is a student already (line 1)"),
        ("ada\nADA\n", "roster.txt:2: ADA is a student already (line 1)"),
        ("ada\nbob smith\n", "roster.txt:2: 'bob smith' cannot be a student's name"),
        ("# nobody yet\n\n", "roster.txt names no student"),
        ("instructor\n", "roster.txt:1: 'instructor' is the instructor's line"),
    ],
)
def test_a_bad_roster_is_one_line_naming_the_line(tmp_path: Path, text: str, says: str) -> None:
    roster = tmp_path / "roster.txt"
    roster.write_text(text)
    with pytest.raises(RosterError) as raised:
        read_roster(roster)
    assert says in str(raised.value) and "\n" not in str(raised.value)


def test_a_roster_that_is_not_there(tmp_path: Path) -> None:
    with pytest.raises(RosterError, match="no such roster file"):
        read_roster(tmp_path / "nope.txt")


def _folders(root: Path, files: dict[str, list[str]]) -> Path:
    for student, names in files.items():
        (root / student).mkdir(parents=True)
        for name in names:
            (root / student / name).write_text("")
    return root


def test_every_folder_is_a_student_without_a_roster(tmp_path: Path) -> None:
    root = _folders(tmp_path / "subs", {"bob": ["b.py", "a.py", "notes.txt"], "ada": ["x.py"], "cyd": [], ".git": ["hook.py"]})
    (root / "README.md").write_text("")
    found = find_submissions(root)
    assert [s.student for s in found.submissions] == ["ada", "bob", "cyd"]
    assert found.submissions[1].files == (root / "bob" / "a.py", root / "bob" / "b.py")
    assert found.submissions[0].missing == ""
    assert found.submissions[2].missing == f"no submission (no .py file in {root / 'cyd'})"
    assert found.not_on_roster == []


def test_the_roster_says_who_is_graded(tmp_path: Path) -> None:
    root = _folders(tmp_path / "subs", {"ada": ["x.py"], "Bob": ["y.py"], "eve": ["z.py"]})
    found = find_submissions(root, ["ada", "bob", "cyd"])
    assert [(s.student, [f.name for f in s.files]) for s in found.submissions] == [("ada", ["x.py"]), ("bob", ["y.py"]), ("cyd", [])]
    assert found.submissions[2].missing == f"no submission (no folder {root / 'cyd'})"
    assert found.not_on_roster == [root / "eve"]


def test_a_folder_with_no_student_or_a_bad_name(tmp_path: Path) -> None:
    (tmp_path / "empty").mkdir()
    with pytest.raises(RosterError, match="no student's folder in it"):
        find_submissions(tmp_path / "empty")
    _folders(tmp_path / "subs", {"ada": [], "ada-2": []})
    with pytest.raises(RosterError, match="'ada-2' cannot be a student's name"):
        find_submissions(tmp_path / "subs")
    _folders(tmp_path / "twins", {"ada": [], "Ada": []})
    with pytest.raises(RosterError, match=r"twins/ada: ada is a student already \(.*twins/Ada\)"):
        find_submissions(tmp_path / "twins")
