"""The robot world's options: ``--robots`` and ``--obstacles`` (``SKYDECK_SIM_ROBOTS``...),
beside every world's (:class:`sim_server.settings.SimSettings`), and a class's students
(``SKYDECK_SIM_STUDENTS``, which ``skydeck class`` sets: not an option of launch files). Pure
settings: importing this loads no PyBullet."""

from __future__ import annotations

import re

from pydantic import Field, field_validator

from sim_server.robot.limits import DEFAULT_OBSTACLES, MAX_CLASS_ROBOTS, MAX_OBSTACLES, MAX_ROBOTS
from sim_server.settings import SimSettings

__all__ = ["RobotSettings"]

_STUDENT = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,62}")  # a namespace's one segment (services/access/tokens.py)


class RobotSettings(SimSettings):
    """The robot world's settings."""

    robots: int = Field(
        default=1, ge=1, le=MAX_ROBOTS, description=f"number of robots, 1-{MAX_ROBOTS} (default 1), under /robot1, /robot2..."
    )
    obstacles: int = Field(
        default=DEFAULT_OBSTACLES,
        ge=0,
        le=MAX_OBSTACLES,
        description=f"number of box obstacles, 0-{MAX_OBSTACLES} (default {DEFAULT_OBSTACLES})",
    )
    students: str = Field(
        default="",
        description=f"a class: comma-separated names, one robot each under /NAME (at most {MAX_CLASS_ROBOTS}); replaces --robots",
    )

    @field_validator("students")
    @classmethod
    def _check_students(cls, value: str) -> str:
        names = [name.strip() for name in value.split(",") if name.strip()]
        bad = next((name for name in names if not _STUDENT.fullmatch(name)), None)
        if bad is not None:
            raise ValueError(f"{bad!r} cannot name a namespace: a letter, then letters, digits or _")
        if len(set(names)) != len(names):
            raise ValueError("a student is named twice")
        if len(names) > MAX_CLASS_ROBOTS:
            raise ValueError(f"{len(names)} students is more than a room holds ({MAX_CLASS_ROBOTS})")
        return ",".join(names)

    @property
    def student_names(self) -> tuple[str, ...]:
        """The class's students, in the roster's order (none: not a class)."""
        return tuple(self.students.split(",")) if self.students else ()

    @classmethod
    def own_options(cls) -> list[str]:
        # A class's students come from `skydeck class` (SKYDECK_SIM_STUDENTS), not from a flag
        # of launch files, whose world options are numbers.
        return [name for name in super().own_options() if name != "students"]
