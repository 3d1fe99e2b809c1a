"""`skydeck class`'s roster, tokens and address: each problem refused in one line (issue 35)."""

from __future__ import annotations

import stat
import subprocess
import sys
from pathlib import Path

import pytest

from services.access import read_tokens
from services.classroom import (
    ClassOptions,
    ClassroomError,
    Roster,
    check_host,
    class_tokens,
    read_roster,
)
from services.classroom.launch import class_spec

pytestmark = pytest.mark.timeout(60)

REPO = Path(__file__).resolve().parents[3]


def _file(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_a_csv_roster_is_its_first_column_under_an_optional_header(tmp_path: Path) -> None:
    roster = _file(tmp_path, "students.csv", "name,email\n# the Monday group\nalice,a@x.org\n\nbob , b@x.org\ncarol # late\n")
    assert read_roster(roster) == Roster(("alice", "bob", "carol"), "robot")


def test_a_yaml_roster_is_a_list_or_students_and_a_world(tmp_path: Path) -> None:
    assert read_roster(_file(tmp_path, "a.yaml", "[alice, bob]\n")).students == ("alice", "bob")
    assert read_roster(_file(tmp_path, "b.yml", "world: robot\nstudents: [carol]\n")) == Roster(("carol",), "robot")


@pytest.mark.parametrize(
    ("name", "text", "said"),
    [
        ("twice.csv", "alice\nbob\nalice\n", "twice.csv:3: alice is a student already (line 1): each student once"),
        ("case.csv", "alice\nAlice\n", "case.csv:2: Alice is a student already (line 1): each student once"),
        ("bad.csv", "alice\nbob smith\n", "bad.csv:2: 'bob smith' cannot be a student's name: a letter, then letters, digits or _ (at most 63), since it names their namespace /NAME"),
        ("teacher.csv", "instructor\n", "teacher.csv:1: 'instructor' is the instructor's line: give the student another name"),
        ("empty.csv", "name\n\n# nobody yet\n", "empty.csv names no student: one name a line"),
        ("twice.yaml", "students: [alice, alice]\n", "twice.yaml: alice is a student already (earlier): each student once"),
        ("drone.yaml", "world: drone\nstudents: [alice]\n", "drone.yaml: world 'drone': a class runs in the robot world (a robot per student); the drone world holds one drone. Write `world: robot` or leave it out"),
        ("typo.yaml", "studnets: [alice]\n", "typo.yaml: unknown key 'studnets': a roster has `students:` and `world:`"),
        ("numbers.yaml", "students: [1, 2]\n", "numbers.yaml: `students:` must be a list of names (e.g. [alice, bob])"),
    ],
)
def test_a_roster_that_cannot_be_used_is_refused_in_one_line(tmp_path: Path, name: str, text: str, said: str) -> None:
    with pytest.raises(ClassroomError) as refused:
        read_roster(_file(tmp_path, name, text))
    assert str(refused.value) == f"{tmp_path}/{said}"


def test_a_roster_larger_than_a_room_is_refused(tmp_path: Path) -> None:
    roster = _file(tmp_path, "big.csv", "".join(f"s{i}\n" for i in range(41)))
    with pytest.raises(ClassroomError, match=r"big.csv names 41 students; a room holds 40 robots: split the class in two$"):
        read_roster(roster)


def test_skydeck_class_says_a_bad_roster_in_one_line_and_writes_no_tokens(tmp_path: Path) -> None:
    roster = _file(tmp_path, "students.csv", "alice\nbob\nalice\n")
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "class", str(roster), "--tokens", str(tmp_path / "t.csv")],
        cwd=REPO, capture_output=True, text=True, timeout=50,
    )  # fmt: skip
    assert done.returncode == 1
    assert done.stderr.strip().splitlines() == [f"skydeck: error: {roster}:3: alice is a student already (line 1): each student once"]
    assert not (tmp_path / "t.csv").exists()


def test_the_tokens_are_written_once_for_the_owner_and_read_back_for_the_same_roster(tmp_path: Path) -> None:
    path = tmp_path / "class-tokens.csv"
    roster = Roster(("alice", "bob"))
    tokens, new = class_tokens(path, roster)
    assert new and set(tokens) == {"alice", "bob", "instructor"} and len(set(tokens.values())) == 3
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert read_tokens(path) == tokens
    again, new = class_tokens(path, Roster(("bob", "alice")))
    assert again == tokens and not new


def test_another_rosters_tokens_file_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "class-tokens.csv"
    class_tokens(path, Roster(("alice", "bob")))
    with pytest.raises(ClassroomError, match=r"holds another class's tokens \(it and the roster differ in bob, carol\): give --tokens NEW_FILE"):
        class_tokens(path, Roster(("alice", "carol")))


@pytest.mark.parametrize("host", ["127.0.0.1", "localhost", "::1", "127.0.0.2"])
def test_loopback_is_always_allowed(host: str) -> None:
    check_host(host, fenced=False)


def test_the_network_is_only_for_a_fenced_core_on_every_interface() -> None:
    check_host("0.0.0.0", fenced=True)
    with pytest.raises(ClassroomError, match=r"^--host 0.0.0.0 opens the core to the network: only a class with tokens may$"):
        check_host("0.0.0.0", fenced=False)
    with pytest.raises(ClassroomError, match=r"^--host 192.168.1.20: a class listens on loopback .* or every interface"):
        check_host("192.168.1.20", fenced=True)


def test_the_launch_is_a_fenced_core_and_a_world_of_the_rosters_robots(tmp_path: Path) -> None:
    options = ClassOptions(tokens=tmp_path / "{odd}.csv", gradebook=tmp_path / "gradebook.json", host="0.0.0.0", advertise="10.0.0.5")
    core, sim = class_spec(Roster(("alice", "bob")), options).nodes
    assert core.is_core and "--class-tokens" in core.args and "--class-gradebook" in core.args
    assert str(tmp_path / "{{odd}}.csv") in core.args  # a literal path, braces and all
    assert tuple(core.args[core.args.index("--host") : core.args.index("--host") + 2]) == ("--host", "0.0.0.0")
    assert "--advertise-url" in core.args and "http://10.0.0.5:8001" in sim.args
    assert sim.env == {"SKYDECK_SIM_STUDENTS": "alice,bob"} and sim.args[:2] == ("--world", "robot")


def test_skydeck_class_refuses_a_single_network_address_in_one_line_before_writing_tokens(tmp_path: Path) -> None:
    roster = _file(tmp_path, "students.csv", "alice\nbob\n")
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "class", str(roster), "--host", "192.168.1.20", "--tokens", str(tmp_path / "t.csv")],
        cwd=REPO, capture_output=True, text=True, timeout=50,
    )  # fmt: skip
    assert done.returncode == 1
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("skydeck: error: --host 192.168.1.20: a class listens on loopback")
    assert not (tmp_path / "t.csv").exists()
