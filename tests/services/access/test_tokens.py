"""A class's tokens: made at random, written once readable by the owner only, read back with one
clear line for each way a file can be wrong, and kept by the core as keyed hashes it compares in
constant time."""

from __future__ import annotations

import hmac
import os
import stat
from pathlib import Path

import pytest

import services.access.tokens as tokens_module
from services.access import (
    INSTRUCTOR,
    ClassTokensError,
    TokenSet,
    make_class_tokens,
    read_tokens,
    write_tokens,
)

pytestmark = pytest.mark.timeout(30)


def test_make_gives_each_student_and_the_instructor_a_random_token() -> None:
    tokens = make_class_tokens(["alice", "bob", "Carol_2"])
    assert list(tokens) == ["alice", "bob", "Carol_2", INSTRUCTOR]
    assert len(set(tokens.values())) == 4 and all(len(token) >= 40 for token in tokens.values())
    assert make_class_tokens(["alice"])["alice"] != make_class_tokens(["alice"])["alice"]


@pytest.mark.parametrize(
    ("names", "said"),
    [
        (["alice", "alice"], "name 2: alice is a student already (name 1): each student once"),
        (["alice", "bob", "Alice"], "name 3: Alice is a student already (name 1)"),
        (["al ice"], "cannot be a student's name"),
        (["1alice"], "cannot be a student's name"),
        (["alice/bob"], "cannot be a student's name"),
        ([""], "cannot be a student's name"),
        (["instructor"], "the instructor's line"),
        ([], "names no student"),
    ],
)
def test_a_roster_with_duplicates_or_bad_names_is_refused_in_one_line(names: list[str], said: str) -> None:
    with pytest.raises(ClassTokensError) as refused:
        make_class_tokens(names)
    assert said in str(refused.value) and "\n" not in str(refused.value)


def test_written_once_readable_by_the_owner_only_and_read_back(tmp_path: Path) -> None:
    path = tmp_path / "class-tokens.csv"
    tokens = make_class_tokens(["alice", "bob"])
    write_tokens(path, tokens)
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert path.read_text().splitlines()[0] == "name,token"
    assert f"alice,{tokens['alice']}" in path.read_text().splitlines()
    assert read_tokens(path) == tokens
    with pytest.raises(ClassTokensError, match="exists: tokens are written once"):
        write_tokens(path, make_class_tokens(["carol"]))
    assert read_tokens(path) == tokens  # untouched


def test_the_mode_is_set_as_the_file_is_made_whatever_the_umask(tmp_path: Path) -> None:
    old = os.umask(0)
    try:
        write_tokens(tmp_path / "t.csv", make_class_tokens(["alice"]))
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "t.csv").stat().st_mode) == 0o600


def _file(tmp_path: Path, text: str, mode: int = 0o600) -> Path:
    path = tmp_path / "tokens.csv"
    path.write_text(text)
    path.chmod(mode)
    return path


GOOD = "x" * 20


@pytest.mark.parametrize(
    ("text", "mode", "said"),
    [
        (f"alice,{GOOD}1\ninstructor,{GOOD}2\n", 0o644, "may be read by others (mode 644): `chmod 600"),
        (f"alice,{GOOD}1\n", 0o600, "has no instructor line"),
        (f"alice,{GOOD}1,extra\ninstructor,{GOOD}2\n", 0o600, "tokens.csv:1: expected `name,token`, got 3 fields"),
        (f"alice,{GOOD}1\nalice,{GOOD}3\ninstructor,{GOOD}2\n", 0o600, "tokens.csv:2: alice is a student already (line 1): each student once"),
        (f"alice,{GOOD}1\ninstructor,{GOOD}2\ninstructor,{GOOD}3\n", 0o600, "tokens.csv:3: the instructor has a line already"),
        (f"alice,short\ninstructor,{GOOD}2\n", 0o600, "tokens.csv:1: alice's token must be at least 16"),
        (f"alice,{GOOD} 1\ninstructor,{GOOD}2\n", 0o600, "no spaces"),
        (f"bob,{GOOD}1\nalice,{GOOD}1\ninstructor,{GOOD}2\n", 0o600, "tokens.csv:2: alice has the token of bob"),
        (f"a-b,{GOOD}1\ninstructor,{GOOD}2\n", 0o600, "tokens.csv:1: 'a-b' cannot be a student's name"),
    ],
)
def test_a_bad_tokens_file_is_refused_naming_the_line(tmp_path: Path, text: str, mode: int, said: str) -> None:
    with pytest.raises(ClassTokensError) as refused:
        read_tokens(_file(tmp_path, text, mode))
    assert said in str(refused.value) and "\n" not in str(refused.value)


def test_header_blank_and_comment_lines_are_skipped(tmp_path: Path) -> None:
    path = _file(tmp_path, f"# for the robotics class\nname,token\n\nalice, {GOOD}1 \ninstructor,{GOOD}2\n")
    assert read_tokens(path) == {"alice": f"{GOOD}1", "instructor": f"{GOOD}2"}


def test_a_missing_file_says_how_to_make_one(tmp_path: Path) -> None:
    with pytest.raises(ClassTokensError, match="skydeck class ROSTER"):
        read_tokens(tmp_path / "nope.csv")


def test_the_token_set_knows_whose_a_token_is_and_keeps_no_token() -> None:
    tokens = make_class_tokens(["alice", "bob"])
    known = TokenSet(tokens)
    assert [known.name_of(tokens[name]) for name in ("alice", "bob", INSTRUCTOR)] == ["alice", "bob", INSTRUCTOR]
    assert known.name_of("") is None and known.name_of(tokens["alice"] + "x") is None
    held = repr(vars(known))
    assert not any(token in held for token in tokens.values())  # only keyed hashes
    assert TokenSet(tokens)._entries != known._entries  # a key of each process's own


def test_a_token_is_compared_with_every_known_one_in_constant_time(monkeypatch: pytest.MonkeyPatch) -> None:
    compared: list[tuple[bytes, bytes]] = []
    compare = hmac.compare_digest

    def spy(a: bytes, b: bytes) -> bool:
        compared.append((a, b))
        return compare(a, b)

    tokens = make_class_tokens(["alice", "bob", "carol"])
    known = TokenSet(tokens)
    monkeypatch.setattr(tokens_module.hmac, "compare_digest", spy)
    for presented in (tokens["alice"], tokens[INSTRUCTOR], "nobody's token at all"):
        compared.clear()
        known.name_of(presented)
        assert len(compared) == 4  # all of them, whichever matches (or none)
