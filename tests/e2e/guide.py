"""Reading a guide in docs/ for the tests that run it: its code blocks and its commands."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

_BLOCK = re.compile(r"```(\w+)\n(.*?)```", re.S)


def code_blocks(guide: Path, language: str) -> list[str]:
    """The bodies of the guide's fenced blocks of ``language``, in order."""
    return [body for lang, body in _BLOCK.findall(guide.read_text()) if lang == language]


def skydeck_commands(guide: Path) -> list[list[str]]:
    """Every ``skydeck ...`` line of the guide's ``sh`` blocks, as arguments after ``skydeck``
    (comments dropped), in order."""
    commands = []
    for block in code_blocks(guide, "sh"):
        for line in block.splitlines():
            line = line.split("#", 1)[0].strip()
            if line.startswith("skydeck "):
                commands.append(shlex.split(line)[1:])
    return commands
