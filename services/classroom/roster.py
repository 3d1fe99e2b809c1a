"""A class's roster: who is in it, and which world they drive in.

    students.csv                      students.yaml
    name                              world: robot
    alice                             students: [alice, bob]
    bob

CSV: one student a line, the name in the first column (a ``name`` header, blank lines and what
follows ``#`` are skipped; other columns are the instructor's own, and ignored): a plain list of
names, one a line, is such a file, the roster ``skydeck grade --class --roster`` reads too. YAML: a list of
names, or ``students:`` and optionally ``world:``. Names are ROS name segments (their namespace
is ``/NAME``), each once (case aside): :func:`services.access.check_class_names`'s rule, so the
tokens file takes them as they are. Every problem is one :class:`ClassroomError` line naming
the file and, where it can, the line.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from pathlib import Path

from services.access import ClassTokensError, check_class_names
from shared_models.errors import SkydeckError
from shared_models.text_files import parse_yaml, read_text_file
from sim_server.robot.limits import MAX_CLASS_ROBOTS  # pure constants: no PyBullet

__all__ = ["CLASS_WORLDS", "ClassroomError", "Roster", "read_roster"]

CLASS_WORLDS = ("robot",)
"""The worlds a class runs in: the robot world holds a robot per student (the drone world one drone)."""
_YAML_SUFFIXES = (".yaml", ".yml")


class ClassroomError(SkydeckError):
    """A roster, an address or a tokens file a class cannot start with (one line: what to do)."""

    http_status = 400


@dataclass(frozen=True)
class Roster:
    """The students, in the roster's order, and their world."""

    students: tuple[str, ...]
    world: str = "robot"


def read_roster(path: Path, *, max_students: int | None = MAX_CLASS_ROBOTS) -> Roster:
    """The roster at ``path`` (CSV, or YAML by its suffix); ClassroomError in one line. A class
    room holds ``max_students`` robots; grading a class reads its roster with no such bound."""
    text = read_text_file(path, "roster file", lambda reason: ClassroomError(f"{path}: {reason} (a CSV of names, one a line: docs/class.md)"))
    if path.suffix.lower() in _YAML_SUFFIXES:
        names, world = _from_yaml(path, text)
    else:
        names, world = _from_csv(path, text), "robot"
    if world not in CLASS_WORLDS:
        raise ClassroomError(
            f"{path}: world {world!r}: a class runs in the robot world (a robot per student); "
            f"the drone world holds one drone. Write `world: robot` or leave it out"
        )
    if not names:
        raise ClassroomError(f"{path} names no student: one name a line")
    students = _check_names([(f"{path}:{number}" if number else str(path), name) for number, name in names])
    if max_students is not None and len(students) > max_students:
        raise ClassroomError(
            f"{path} names {len(students)} students; a room holds {max_students} robots: split the class in two"
        )
    return Roster(students, world)


def _from_csv(path: Path, text: str) -> list[tuple[int, str]]:
    names: list[tuple[int, str]] = []
    for number, row in enumerate(csv.reader(io.StringIO(text)), start=1):
        name = row[0].split("#", 1)[0].strip() if row else ""  # what follows # is a comment
        if not name or (not names and name.lower() == "name"):
            continue
        names.append((number, name))
    return names


def _from_yaml(path: Path, text: str) -> tuple[list[tuple[int, str]], str]:
    data = parse_yaml(text, lambda reason: ClassroomError(f"{path}: {reason}"))
    world: object = "robot"
    if isinstance(data, dict):
        unknown = sorted(str(key) for key in data if key not in ("students", "world"))
        if unknown:
            raise ClassroomError(f"{path}: unknown key {unknown[0]!r}: a roster has `students:` and `world:`")
        world = data.get("world", "robot")
        data = data.get("students")
    if not isinstance(data, list) or not all(isinstance(name, str) for name in data):
        raise ClassroomError(f"{path}: `students:` must be a list of names (e.g. [alice, bob])")
    if not isinstance(world, str):
        raise ClassroomError(f"{path}: `world:` must be a world's name (robot)")
    return [(0, name.strip()) for name in data], world


def _check_names(names: list[tuple[str, str]]) -> tuple[str, ...]:
    """The class's rule for its students' names (:func:`services.access.check_class_names`), each
    with where it was found (``FILE:LINE``, a folder), as a ClassroomError."""
    try:
        return check_class_names(names)
    except ClassTokensError as error:
        raise ClassroomError(str(error)) from None
