"""Keys in a terminal while a recording plays: the space bar pauses and resumes (rosbag play)."""

from __future__ import annotations

import asyncio
import contextlib
import os
import sys
from collections.abc import Callable, Iterator

__all__ = ["space_bar"]


@contextlib.contextmanager
def space_bar(on_space: Callable[[], None]) -> Iterator[bool]:
    """While inside, each space typed calls ``on_space``; yields whether a terminal is there.

    The terminal is put in cbreak mode (keys arrive one by one, not echoed) and restored on
    the way out. Without a terminal on standard input (a pipe, a test, CI) nothing changes.
    """
    if not sys.stdin.isatty():
        yield False
        return
    import termios
    import tty

    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd)
    loop = asyncio.get_running_loop()

    def on_readable() -> None:
        try:
            keys = os.read(fd, 32)
        except OSError:
            return
        for _ in range(keys.count(b" ")):
            on_space()

    tty.setcbreak(fd, termios.TCSANOW)  # keeps keys typed before (TCSAFLUSH would drop them)
    loop.add_reader(fd, on_readable)
    try:
        yield True
    finally:
        loop.remove_reader(fd)
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
