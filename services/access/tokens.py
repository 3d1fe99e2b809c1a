"""A class's tokens: one per student and one for the instructor, made once, kept as keyed hashes.

    tokens = make_class_tokens(["alice", "bob"])   # {"alice": "...", "bob": "...", "instructor": "..."}
    write_tokens(Path("class-tokens.csv"), tokens) # once: mode 0600, never over an existing file
    tokens = read_tokens(Path("class-tokens.csv")) # what the core reads at start-up
    known = TokenSet(tokens)                       # keyed hashes only: known.name_of(token)

The file is CSV, one ``name,token`` line per student and one for the instructor (``instructor``),
under a ``name,token`` header; blank lines and ``#`` lines are skipped. It is the only place the
tokens are written: the instructor hands each student their line. It is created readable by its
owner alone (0600) and never overwritten; a file others may read is refused when it is read, as
ssh refuses a private key others can read.

Tokens are 32 random bytes (``secrets``), so a keyed hash (HMAC-SHA256 under a key made at
start-up and never stored) is enough to keep them out of the core's memory: a slow hash protects
secrets people choose, and nobody chooses these. :class:`TokenSet` compares a presented token
with every known one in constant time, whichever matches (or none).
"""

from __future__ import annotations

import csv
import hashlib
import hmac
import io
import os
import re
import secrets
import stat
from collections.abc import Iterable, Mapping
from pathlib import Path

from shared_models.errors import SkydeckError

__all__ = [
    "INSTRUCTOR",
    "MIN_TOKEN_LENGTH",
    "ClassTokensError",
    "TokenSet",
    "check_class_names",
    "check_student_name",
    "make_class_tokens",
    "read_tokens",
    "write_tokens",
]

INSTRUCTOR = "instructor"
"""The instructor's line in the tokens file (a name no student may have)."""

MIN_TOKEN_LENGTH = 16
_HEADER = ("name", "token")
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,62}")
_TOKEN = re.compile(r"[\x21-\x7e]+")  # printable ASCII, no spaces: it travels in headers and URLs
_TOKEN_BYTES = 32


class ClassTokensError(SkydeckError):
    """A roster name or a tokens file that cannot be used (the message says which and why)."""

    http_status = 400


def check_student_name(name: str) -> str:
    """``name`` if it can be a student's (a ROS name segment: their namespace is ``/NAME``);
    ClassTokensError otherwise."""
    if not _NAME.fullmatch(name):
        raise ClassTokensError(
            f"{name!r} cannot be a student's name: a letter, then letters, digits or _ (at most 63), "
            "since it names their namespace /NAME"
        )
    if name == INSTRUCTOR:
        raise ClassTokensError(f"{INSTRUCTOR!r} is the instructor's line: give the student another name")
    return name


class _StudentNames:
    """The class's one rule for a list of students: each a student's name
    (:func:`check_student_name`) and none twice in any case. Each name comes with where it was
    found (``FILE:LINE``, a folder, ``name 3``), which a refusal names."""

    def __init__(self) -> None:
        self._first: dict[str, str] = {}  # the name in lower case -> where it was first

    def add(self, where: str, name: str) -> str:
        try:
            check_student_name(name)
        except ClassTokensError as error:
            raise ClassTokensError(_at(where, str(error))) from None
        first = self._first.get(name.lower())
        if first is not None:
            raise ClassTokensError(_at(where, f"{name} is a student already ({_earlier(first, where)}): each student once"))
        self._first[name.lower()] = where
        return name


def check_class_names(names: Iterable[tuple[str, str]]) -> tuple[str, ...]:
    """The names of ``(where, name)`` pairs, each a student's name and none twice in any case;
    ClassTokensError naming the place otherwise (``roster.csv:3: alice is a student already
    (line 1): each student once``)."""
    students = _StudentNames()
    return tuple(students.add(where, name) for where, name in names)


def _at(where: str, problem: str) -> str:
    return f"{where}: {problem}" if where else problem


def _earlier(first: str, where: str) -> str:
    """Where the first of two alike names is, said from the second's place: a line of the same
    file, ``earlier`` (the same place: a YAML list), or the other place (a folder)."""
    first_file, _, first_line = first.rpartition(":")
    if first_line.isdigit() and first_file == where.rpartition(":")[0]:
        return f"line {first_line}"
    return "earlier" if first == where else first


def make_class_tokens(names: Iterable[str]) -> dict[str, str]:
    """A new random token for each student of ``names`` and one for the instructor (last).

    ClassTokensError for a bad or repeated name (one line naming it).
    """
    students = check_class_names((f"name {number}", name) for number, name in enumerate(names, start=1))
    if not students:
        raise ClassTokensError("the roster names no student")
    tokens = {name: secrets.token_urlsafe(_TOKEN_BYTES) for name in students}
    tokens[INSTRUCTOR] = secrets.token_urlsafe(_TOKEN_BYTES)
    return tokens


def write_tokens(path: Path, tokens: Mapping[str, str]) -> None:
    """Write ``tokens`` to a new file at ``path``, readable by its owner only (0600).

    ClassTokensError if the file exists (tokens are written once: remove it to make new ones).
    """
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(_HEADER)
    writer.writerows(tokens.items())
    try:
        # O_EXCL: never over an existing file (nor through a link someone left there); the mode
        # is set as the file is made, so it is never readable by others, not even for a moment.
        descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except FileExistsError:
        raise ClassTokensError(f"{path} exists: tokens are written once; remove it to make new ones") from None
    except OSError as error:
        raise ClassTokensError(f"cannot write {path}: {error.strerror or error}") from None
    with os.fdopen(descriptor, "w", encoding="utf-8") as file:
        file.write(text.getvalue())


def read_tokens(path: Path) -> dict[str, str]:
    """The tokens of the file at ``path`` (name -> token, the instructor's under ``instructor``).

    ClassTokensError, naming the file and the line, for a file others may read, a line that is
    not ``name,token``, a bad or repeated name, a short token, a token given twice, or no
    instructor line.
    """
    try:
        mode = path.stat().st_mode
        if mode & (stat.S_IRWXG | stat.S_IRWXO):
            raise ClassTokensError(
                f"{path} may be read by others (mode {stat.S_IMODE(mode):o}): `chmod 600 {path}`, then start again"
            )
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ClassTokensError(f"no tokens file {path}: `skydeck class ROSTER` writes one") from None
    except (OSError, UnicodeDecodeError) as error:
        raise ClassTokensError(f"cannot read {path}: {getattr(error, 'strerror', None) or error}") from None
    tokens: dict[str, str] = {}
    owners: dict[str, str] = {}  # token -> name
    students = _StudentNames()
    for number, row in enumerate(csv.reader(io.StringIO(text)), start=1):
        if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
            continue
        where = f"{path}:{number}"
        fields = tuple(field.strip() for field in row)
        if fields == _HEADER:
            continue
        if len(fields) != 2:
            raise ClassTokensError(f"{where}: expected `name,token`, got {len(fields)} fields")
        name, token = fields
        if name != INSTRUCTOR:
            students.add(where, name)
        elif INSTRUCTOR in tokens:
            raise ClassTokensError(f"{where}: the instructor has a line already: one line each")
        if len(token) < MIN_TOKEN_LENGTH or not _TOKEN.fullmatch(token):
            raise ClassTokensError(
                f"{where}: {name}'s token must be at least {MIN_TOKEN_LENGTH} printable characters with no "
                "spaces (`skydeck class` makes them)"
            )
        if token in owners:
            raise ClassTokensError(f"{where}: {name} has the token of {owners[token]}: each needs their own")
        owners[token] = name
        tokens[name] = token
    if INSTRUCTOR not in tokens:
        raise ClassTokensError(f"{path} has no {INSTRUCTOR} line: the instructor needs a token too")
    return tokens


class TokenSet:
    """A class's tokens as keyed hashes: who presented a token, never the tokens themselves."""

    def __init__(self, tokens: Mapping[str, str]) -> None:
        self._key = secrets.token_bytes(32)  # this process's alone: the hashes mean nothing elsewhere
        self._entries = [(self._digest(token), name) for name, token in tokens.items()]

    def _digest(self, token: str) -> bytes:
        return hmac.new(self._key, token.encode(), hashlib.sha256).digest()

    @property
    def names(self) -> list[str]:
        """Everyone with a token: the students, then the instructor (as the file lists them)."""
        return [name for _, name in self._entries]

    def name_of(self, token: str) -> str | None:
        """Whose ``token`` this is, if anyone's. Every known hash is compared, in constant time,
        whichever matches: the time taken says nothing about the tokens."""
        if not token:
            return None
        presented = self._digest(token)
        found = None
        for digest, name in self._entries:
            if hmac.compare_digest(presented, digest):
                found = name
        return found
