"""Reading a text file a user names (a launch file, an assignment, a roster): one wording for
what can go wrong, raised as the caller's own error.

    text = read_text_file(path, "roster file", lambda reason: RosterError(f"{path}: {reason}"))
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

__all__ = ["read_text_file"]


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
