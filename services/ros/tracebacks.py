"""The traceback a user sees when their own callback raises: their frames, not Skydeck's.

    Traceback (most recent call last):
      File "/home/me/my_node.py", line 21, in process_scan
        self.distance = msg.ranges[400]
    IndexError: list index out of range

Frames of Skydeck's code (the executor that called the callback, the API the callback called
into) and of the standard library's threading around them are left out at both ends, so the
first and last lines are the user's; if no frame is the user's the whole traceback is kept.
"""

from __future__ import annotations

import threading
import traceback
from pathlib import Path

import services
import shared_models

__all__ = ["user_traceback"]

_OURS = tuple(
    str(Path(package.__file__).resolve().parent) + "/" for package in (services, shared_models) if package.__file__
)
_THREADING = str(Path(threading.__file__).resolve()) if threading.__file__ else ""


def _is_ours(filename: str) -> bool:
    path = str(Path(filename).resolve())
    return path == _THREADING or path.startswith(_OURS)


def user_traceback(error: BaseException) -> str:
    """``error``'s traceback as Python prints it, trimmed to the user's frames (see above)."""
    frames = traceback.extract_tb(error.__traceback__)
    theirs = [index for index, frame in enumerate(frames) if not _is_ours(frame.filename)]
    if theirs:
        frames = traceback.StackSummary.from_list(frames[theirs[0] : theirs[-1] + 1])
    lines = ["Traceback (most recent call last):\n", *frames.format(), *traceback.format_exception_only(error)]
    return "".join(lines).rstrip("\n")
