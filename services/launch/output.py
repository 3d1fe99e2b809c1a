"""A launch's lines on its terminal: the supervisor's (``[launch] ...``) and its children's
(``[name] ...``), written whole and at once."""

from __future__ import annotations

import contextlib
import sys
from typing import TextIO

__all__ = ["say", "write_line"]


def write_line(out: TextIO | None, line: str) -> None:
    """``line`` on ``out`` (default: standard output), flushed. A closed or broken terminal must
    not stop the supervision of the nodes: what cannot be written is dropped."""
    stream = out or sys.stdout
    with contextlib.suppress(OSError, ValueError):
        stream.write(line + "\n")
        stream.flush()


def say(out: TextIO | None, text: str) -> None:
    """One of the launch's own lines (``[launch] text``)."""
    write_line(out, f"[launch] {text}")
