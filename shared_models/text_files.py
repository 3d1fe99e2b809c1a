"""Reading a text a user gives (a launch file, an assignment, a roster, a params file, a
command line's DATA): one wording for what can go wrong, raised as the caller's own error.

    text = read_text_file(path, "roster file", lambda reason: RosterError(f"{path}: {reason}"))
    data = parse_yaml(text, lambda reason: RosterError(f"{path}: {reason}"))
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import yaml

__all__ = ["YamlProblem", "parse_yaml", "read_text_file"]


def read_text_file(path: Path, what: str, error: Callable[[str], Exception]) -> str:
    """The file's UTF-8 text; a missing, unreadable or non-UTF-8 file raises ``error(reason)``
    (``no such WHAT``, ``is a folder, not a WHAT``, ``cannot read it: ...``)."""
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise error(f"no such {what}") from None
    except IsADirectoryError:
        raise error(f"is a folder, not a {what}") from None
    except (OSError, UnicodeDecodeError) as problem:
        raise error(f"cannot read it: {getattr(problem, 'strerror', None) or problem}") from None


class YamlProblem(str):
    """What :func:`parse_yaml` says of a syntax error: ``YAML syntax error at line L, column C:
    PROBLEM``, with ``line`` (1-based, 0 when YAML did not say) and ``problem`` apart for a
    caller that puts the line elsewhere (``FILE:LINE: ...``)."""

    line: int
    problem: str

    def __new__(cls, problem: str, line: int = 0, column: int = 0) -> YamlProblem:
        where = f" at line {line}, column {column}" if line else ""
        reason = super().__new__(cls, f"YAML syntax error{where}: {problem}")
        reason.line, reason.problem = line, problem
        return reason


def parse_yaml(text: str, error: Callable[[YamlProblem], Exception], *, nodes: bool = False) -> Any:
    """The document in ``text`` (``yaml.safe_load``'s values, or with ``nodes`` ``yaml.compose``'s
    nodes, which keep their lines); a syntax error raises ``error(reason)``, the reason a
    :class:`YamlProblem`."""
    try:
        return yaml.compose(text) if nodes else yaml.safe_load(text)
    except yaml.YAMLError as raised:
        mark = getattr(raised, "problem_mark", None)
        what = getattr(raised, "problem", None) or str(raised).splitlines()[0]
        place = (mark.line + 1, mark.column + 1) if mark is not None else ()
        raise error(YamlProblem(what, *place)) from None
