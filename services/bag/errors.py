"""The errors of recording and playback, each one line that names the cause and what to do.

BagError                a recording cannot be made or played (an output that cannot be written,
│                       a topic that cannot be recorded)
└── BagFileError        a file is not a readable recording (missing, not MCAP, nothing left)
"""

from __future__ import annotations

from pathlib import Path

from shared_models.errors import SkydeckError

__all__ = ["BagError", "BagFileError"]


class BagError(SkydeckError):
    """A recording cannot be made or played; the message says why and what to do."""

    http_status = 400


class BagFileError(BagError):
    """The file at ``path`` is not a recording that can be read; ``problem`` says why."""

    def __init__(self, path: Path | str, problem: str) -> None:
        super().__init__(f"{path}: {problem}")
        self.path = Path(path)
        self.problem = problem
