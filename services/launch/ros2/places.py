"""Where in the user's launch file a thing was written: ``talk.launch.py:12``.

A Python launch file's actions are made by its own code, so each one records the line of the
user's file that made it (:func:`caller_place`): the files being read are kept here while they
run (:func:`reading`). XML and YAML launch files give their elements' lines directly.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from services.launch.errors import LaunchFileError
from services.launch.ros2.packages import Workspace

__all__ = ["Place", "caller_place", "current_workspace", "not_provided", "reading"]

_READING: list[str] = []  # the Python launch files being run now, innermost last
_WORKSPACES: list[Workspace] = []  # and the workspace each is read in


class Place:
    """A file and a line (0: the line is not known)."""

    def __init__(self, file: Path, line: int = 0) -> None:
        self.file = file
        self.line = line

    def __str__(self) -> str:
        return f"{self.file}:{self.line}" if self.line else str(self.file)

    def error(self, problem: str) -> LaunchFileError:
        """One line: ``FILE:LINE: problem``."""
        return LaunchFileError(str(self), problem)


@contextmanager
def reading(path: Path, workspace: Workspace) -> Iterator[None]:
    """While ``path``'s code runs, :func:`caller_place` finds its lines and
    :func:`current_workspace` is ``workspace``."""
    _READING.append(str(path))
    _WORKSPACES.append(workspace)
    try:
        yield
    finally:
        _READING.pop()
        _WORKSPACES.pop()


def current_workspace() -> Workspace:
    """The workspace of the launch file being run (``get_package_share_directory`` looks there)."""
    return _WORKSPACES[-1] if _WORKSPACES else Workspace([Path.cwd()])


def caller_place() -> Place:
    """The line of the launch file being run that called into us (the innermost such frame)."""
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_filename in _READING:
            return Place(Path(frame.f_code.co_filename), frame.f_lineno)
        frame = frame.f_back  # type: ignore[assignment]
    return Place(Path(_READING[-1]) if _READING else Path("<launch>"))


def not_provided(what: str, provided: list[str] | None = None) -> LaunchFileError:
    """``FILE:LINE: launch.actions.X is not provided by Skydeck`` at the user's line."""
    also = f" (Skydeck's has: {', '.join(provided)})" if provided else ""
    return caller_place().error(f"{what} is not provided by Skydeck{also}")
