"""Who is graded in class mode, and which files are theirs: students' names, the roster file and
the submissions folder (``skydeck grade ASSIGNMENT.yaml --class SUBMISSIONS [--roster FILE]``).

    names = read_roster(Path("roster.txt"))        # one name a line, '#' comments
    found = find_submissions(Path("submissions"), names)
    found.submissions[0].files                   # submissions/ada/*.py, sorted

A student's name is the class's (:mod:`services.classroom.roster`, ``skydeck class``'s roster):
a ROS name segment, ``/NAME`` their namespace, here their folder; not ``instructor``; two names
that differ only in case are one student twice.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from services.access import ClassTokensError, check_class_names
from services.access import check_student_name as check_student_name_of_class
from services.classroom.roster import ClassroomError
from services.classroom.roster import read_roster as read_class_roster
from shared_models.errors import SkydeckError

__all__ = ["Found", "RosterError", "Submission", "check_student_name", "find_submissions", "read_roster"]

class RosterError(SkydeckError):
    """A roster or a submissions folder that cannot be graded (the message says which and why)."""


def check_student_name(name: str) -> str:
    """``name`` if it can be a student's (the class's rule), else RosterError saying why."""
    try:
        return check_student_name_of_class(name)
    except ClassTokensError as error:
        raise RosterError(str(error)) from None


def read_roster(path: Path) -> list[str]:
    """The students of a roster file, as ``skydeck class`` reads it (a class of any size here)."""
    try:
        return list(read_class_roster(path, max_students=None).students)
    except ClassroomError as error:
        raise RosterError(str(error)) from None


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
        try:
            names = check_class_names((str(entry), entry.name) for entry in folders)
        except ClassTokensError as error:
            raise RosterError(str(error)) from None
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
