"""What ``skydeck launch`` tells a user once every node is up: the pages to open and one
command to try, written so that it works as printed in a new terminal.

    for line in next_steps("http://127.0.0.1:8000"):
        print(line)
    # open http://127.0.0.1:8000/ (the dashboard) and http://127.0.0.1:8000/docs (every command)
    # try, in another terminal: source /home/me/skydeck/.venv/bin/activate && skydeck topic list

A new terminal does not have a virtual environment's ``bin`` on its PATH unless the user put it
there for good (a container's ``ENV PATH``, a shell profile), so the command starts with
``source .../activate`` (its absolute path: a new terminal opens in another folder) whenever
this ``skydeck`` would not be found there.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from pathlib import Path

from services.runtime.settings import DEFAULT_CORE_URL

__all__ = ["TRY_COMMAND", "next_steps", "shell_prefix"]

TRY_COMMAND = "skydeck topic list"
"""The one command to try first: it works in every world and shows what the system has."""


def next_steps(core_url: str, *, environ: Mapping[str, str] | None = None) -> list[str]:
    """The lines to print once every node of a launch that started the core is up."""
    environ = os.environ if environ is None else environ
    url = core_url.rstrip("/")
    # Another port than the default: the CLI in the new terminal must be told where the core is.
    where = "" if url == DEFAULT_CORE_URL.rstrip("/") else f"SKYDECK_CORE_URL={url} "
    return [
        f"open {url}/ (the dashboard) and {url}/docs (every command)",
        f"try, in another terminal: {shell_prefix(environ=environ)}{where}{TRY_COMMAND}",
    ]


def shell_prefix(*, environ: Mapping[str, str], venv: Path | None = None) -> str:
    """``source VENV/bin/activate && `` when a new terminal would not find this ``skydeck``; ``""``
    when it would (not in a virtual environment, or its ``bin`` on PATH without an activation).
    ``venv`` is the environment to speak of (default: this interpreter's, if it runs in one).

    ``VIRTUAL_ENV`` is set by ``activate``: a PATH it made lasts only in that terminal.
    """
    if venv is None:
        if sys.prefix == sys.base_prefix:
            return ""  # a system or --user install: its skydeck is wherever pip put it on PATH
        venv = Path(sys.prefix)
    bin_dir = venv.absolute() / "bin"
    on_path = any(_same(Path(entry), bin_dir) for entry in environ.get("PATH", "").split(os.pathsep) if entry)
    if on_path and not environ.get("VIRTUAL_ENV"):
        return ""
    return f"source {bin_dir / 'activate'} && "


def _same(a: Path, b: Path) -> bool:
    try:
        return a.resolve() == b.resolve()
    except OSError:
        return False
