"""The mission's progress on disk, per world, so a restarted AI never visits a box twice.

A world is known by its boxes: the key is a digest of their positions rounded to a metre (the
boxes settle within centimetres run to run; a reset drops a new set, and so a new key). Each
write goes to a temporary file that replaces the old one atomically (fsync, then rename), so a
crash at any moment leaves either the old progress or the new, never a torn file.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import logging
import os
import tempfile
from collections.abc import Sequence
from pathlib import Path

__all__ = ["ProgressStore", "default_state_dir", "world_key"]

logger = logging.getLogger("skydeck.ai")


def default_state_dir() -> Path:
    """``SKYDECK_STATE_DIR``, else ``$XDG_STATE_HOME/skydeck``, else ``~/.local/state/skydeck``."""
    if configured := os.environ.get("SKYDECK_STATE_DIR"):
        return Path(configured)
    base = os.environ.get("XDG_STATE_HOME") or str(Path.home() / ".local" / "state")
    return Path(base) / "skydeck"


def world_key(boxes: Sequence[tuple[float, float]]) -> str:
    """A short stable name for the world these boxes belong to."""
    rounded = ";".join(f"{round(x):d},{round(y):d}" for x, y in boxes)
    return hashlib.sha256(rounded.encode()).hexdigest()[:16]


class ProgressStore:
    """Visited box indices per world key, in a JSON file under ``directory``."""

    def __init__(self, directory: Path) -> None:
        self.path = directory / "ai_progress.json"

    def load(self, key: str) -> list[int]:
        """The boxes visited in world ``key``, in visiting order (empty if none or unreadable)."""
        return list(self._read().get(key, []))

    def save(self, key: str, visited: Sequence[int]) -> None:
        """Record the visited boxes of world ``key`` (atomically)."""
        data = self._read()
        data[key] = list(visited)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd, temporary = tempfile.mkstemp(dir=self.path.parent, prefix=".ai_progress.", suffix=".tmp")
        try:
            with os.fdopen(fd, "w") as handle:
                json.dump(data, handle)
                handle.flush()
                os.fsync(handle.fileno())
            os.replace(temporary, self.path)
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(temporary)
            raise

    def _read(self) -> dict[str, list[int]]:
        try:
            data = json.loads(self.path.read_text())
        except FileNotFoundError:
            return {}
        except (OSError, ValueError) as error:
            logger.warning("ignoring unreadable progress file %s: %s", self.path, error)
            return {}
        if not isinstance(data, dict):
            return {}
        return {
            str(k): [int(i) for i in v if isinstance(i, int)] for k, v in data.items() if isinstance(v, list)
        }
