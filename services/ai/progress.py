"""The mission's progress on disk, per world, so a restarted AI never visits a box twice.

A world is one *build* of the simulator's world, known by the random id the simulator publishes
on ``/simulator/world`` (a new one at start, at every reset, and when a restarted simulator
builds its world again): a rerun of the same seed is a new world and gets a new tour, while an
AI restarted in the middle of a mission finds its world's progress and carries on.

The file (``ai_progress.json`` in the process's state directory,
``ProcessSettings.skydeck_state_dir``) keeps the last ``KEEP_WORLDS``
worlds, most recent last. Each write goes to a temporary file that replaces the old one
atomically (fsync, then rename), so a crash at any moment leaves either the old progress or the
new, never a torn file. A file that cannot be read or is not ours is ignored with a warning (the
next save replaces it); a save that fails is reported and the mission goes on.
"""

from __future__ import annotations

import contextlib
import logging
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError

__all__ = ["FILE_NAME", "KEEP_WORLDS", "ProgressStore", "WorldProgress"]

logger = logging.getLogger("skydeck.ai")

FILE_NAME = "ai_progress.json"
KEEP_WORLDS = 5


class WorldProgress(BaseModel):
    """One world's mission: its boxes, those visited (in order), and whether it is finished."""

    model_config = ConfigDict(extra="forbid")

    world: str = Field(min_length=1)
    boxes: int = Field(ge=0)
    visited: list[int] = Field(default_factory=list)
    done: bool = False


class _ProgressFile(BaseModel):
    model_config = ConfigDict(extra="forbid")

    version: Literal[2]
    worlds: list[WorldProgress] = Field(default_factory=list)


class ProgressStore:
    """The progress of the last few worlds, in ``directory/ai_progress.json``; problems with
    the file go to ``warn`` (the AI passes its node logger's, so they reach ``/rosout``)."""

    def __init__(self, directory: Path, *, warn: Callable[[str], None] | None = None) -> None:
        self.path = directory / FILE_NAME
        self._warn = warn or logger.warning
        self._worlds: list[WorldProgress] | None = None  # read on first use, then kept
        self._reported: set[str] = set()

    def load(self, world: str) -> WorldProgress | None:
        """The saved progress of ``world``, or None if there is none."""
        return next((p.model_copy(deep=True) for p in self._read() if p.world == world), None)

    def save(self, progress: WorldProgress) -> None:
        """Record ``progress`` as the most recent world, forget all but the last KEEP_WORLDS,
        and write the file atomically. A failed write is logged (once per cause), not raised."""
        worlds = [p for p in self._read() if p.world != progress.world]
        worlds.append(progress.model_copy(deep=True))
        self._worlds = worlds[-KEEP_WORLDS:]
        try:
            self._write(_ProgressFile(version=2, worlds=self._worlds).model_dump_json())
        except OSError as error:
            self._warn_once(
                f"cannot save the AI's progress to {self.path}: {error.strerror or error};"
                " a restarted AI may fly this world again"
            )

    def _read(self) -> list[WorldProgress]:
        if self._worlds is None:
            self._worlds = self._load_file()
        return self._worlds

    def _load_file(self) -> list[WorldProgress]:
        try:
            text = self.path.read_text()
        except FileNotFoundError:
            return []
        except (OSError, UnicodeDecodeError) as error:
            self._warn_once(f"ignoring the AI's progress file {self.path}: cannot read it ({error})")
            return []
        try:
            return _ProgressFile.model_validate_json(text).worlds
        except ValidationError as error:
            first = error.errors()[0]
            where = ".".join(str(part) for part in first["loc"]) or "the file"
            self._warn_once(
                f"ignoring the AI's progress file {self.path}: not a progress file of this version"
                f" ({where}: {first['msg']}); it is replaced at the next save"
            )
            return []

    def _write(self, text: str) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd, temporary = tempfile.mkstemp(dir=self.path.parent, prefix=".ai_progress.", suffix=".tmp")
        try:
            with os.fdopen(fd, "w") as handle:
                handle.write(text)
                handle.flush()
                os.fsync(handle.fileno())
            os.replace(temporary, self.path)
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(temporary)
            raise

    def _warn_once(self, text: str) -> None:
        if text not in self._reported:
            self._reported.add(text)
            self._warn(text)
