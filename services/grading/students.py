"""Who is graded in class mode, and which files are theirs: students' names, the roster file and
the submissions folder (``skydeck grade ASSIGNMENT.yaml --class SUBMISSIONS [--roster FILE]``).

    names = read_roster(Path("roster.txt"))        # one name a line, '#' comments
    found = find_submissions(Path("submissions"), names)
    found.submissions[0].files                   # submissions/ada/*.py, sorted

A student's name is a ROS name segment (a letter, then letters, digits or ``_``, at most 63): in
a class it names the student's namespace ``/NAME``, here their folder. ``instructor`` is the
instructor's, and two names that differ only in case are one student twice. These are the class's
rules for a roster (``skydeck class``'s tokens follow them too).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from shared_models.errors import SkydeckError

__all__ = ["INSTRUCTOR", "Found", "RosterError", "Submission", "check_student_name", "find_submissions", "read_roster"]

INSTRUCTOR = "instructor"
"""The instructor's name in a class (no student may have it)."""

_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,62}")


class RosterError(SkydeckError):
    """A roster or a submissions folder that cannot be graded (the message says which and why)."""


def check_student_name(name: str) -> str:
    """``name`` if it can be a student's, else RosterError saying why."""
    if not _NAME.fullmatch(name):
        raise RosterError(
            f"{name!r} cannot be a student's name: a letter, then letters, digits or _ (at most 63), "
            "since it names their namespace /NAME"
        )
    if name == INSTRUCTOR:
        raise RosterError(f"{INSTRUCTOR!r} is the instructor's name: give the student another")
    return name


def _check_names(names: list[tuple[str, str]]) -> list[str]:
    """The names, each checked, none twice (in any case); ``where`` of each says where it is."""
    seen: dict[str, str] = {}
    for where, name in names:
        try:
            check_student_name(name)
        except RosterError as error:
            raise RosterError(f"{where}: {error}") from None
        twin = seen.get(name.lower())
        if twin is not None:
            same = "twice" if twin == name else f"as {twin!r} and {name!r} (names differ in more than case)"
            raise RosterError(f"{where}: {name!r} is named {same}: each student needs a name of their own")
        seen[name.lower()] = name
    return [name for _, name in names]


def read_roster(path: Path) -> list[str]:
    """The students of a roster file: one name a line; blank lines and what follows ``#`` skipped."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise RosterError(f"no roster file {path}") from None
    except (OSError, UnicodeDecodeError) as error:
        raise RosterError(f"{path}: cannot read the roster: {getattr(error, 'strerror', None) or error}") from None
    names = []
    for number, line in enumerate(text.splitlines(), start=1):
        name = line.split("#", 1)[0].strip()
        if name:
            names.append((f"{path}:{number}", name))
    if not names:
        raise RosterError(f"{path}: the roster names no student")
    return _check_names(names)


@dataclass(frozen=True)
class Submission:
    """One student's files (``SUBMISSIONS/NAME/*.py``, sorted); none: nothing to grade."""

    student: str
    files: tuple[Path, ...]
    folder: Path

    @property
    def missing(self) -> str:
        """Why there is nothing to grade ('' when there is)."""
        if self.files:
            return ""
        if not self.folder.is_dir():
            return f"no submission (no folder {self.folder})"
        return f"no submission (no .py file in {self.folder})"


@dataclass
class Found:
    """What a submissions folder holds: a submission per student, and the folders not graded."""

    submissions: list[Submission]
    not_on_roster: list[Path] = field(default_factory=list)


def find_submissions(folder: Path, roster: list[str] | None = None) -> Found:
    """Every student's files in ``folder`` (``folder/NAME/*.py``): the roster's students if one is
    given (a folder not on it is not graded), else every folder's (its name checked). Hidden
    entries and plain files in ``folder`` are not students."""
    if not folder.is_dir():
        raise RosterError(f"{folder}: no such folder (the submissions: one folder per student, NAME/*.py)")
    folders = sorted(entry for entry in folder.iterdir() if entry.is_dir() and not entry.name.startswith("."))
    if roster is None:
        names = _check_names([(str(entry), entry.name) for entry in folders])
        if not names:
            raise RosterError(f"{folder}: no student's folder in it (one folder per student, NAME/*.py)")
        return Found([_submission(folder, name) for name in names])
    known = {name.lower() for name in roster}
    strangers = [entry for entry in folders if entry.name.lower() not in known]
    by_lower = {entry.name.lower(): entry.name for entry in folders}
    # A folder named in another case than the roster is still the student's (file systems differ).
    submissions = [_submission(folder, name, by_lower.get(name.lower(), name)) for name in roster]
    return Found(submissions, strangers)


def _submission(folder: Path, student: str, folder_name: str | None = None) -> Submission:
    own = folder / (folder_name or student)
    files = tuple(sorted(path for path in own.glob("*.py") if path.is_file())) if own.is_dir() else ()
    return Submission(student, files, own)
