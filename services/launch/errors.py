"""The launcher's errors, each one line that names the cause.

LaunchError              a launch cannot go ahead or a node cannot start at all
└── LaunchFileError      the launch file is missing, not YAML, or not a valid launch file
"""

from __future__ import annotations

from pathlib import Path

from shared_models.errors import SkydeckError

__all__ = ["LaunchError", "LaunchFileError", "read_launch_text"]


class LaunchError(SkydeckError):
    """A launch cannot go ahead: bad options, a port in use, or a node that never became ready.

    ``node`` names the node at fault (if one is), ``exit_code`` is its exit status if it exited,
    and ``stderr_tail`` holds its last lines of standard error.
    """

    def __init__(
        self,
        message: str,
        *,
        node: str | None = None,
        exit_code: int | None = None,
        stderr_tail: tuple[str, ...] = (),
    ) -> None:
        super().__init__(message)
        self.node = node
        self.exit_code = exit_code
        self.stderr_tail = stderr_tail


class LaunchFileError(LaunchError):
    """The launch file at ``path`` cannot be used; ``problem`` says where and why."""

    def __init__(self, path: Path | str, problem: str) -> None:
        super().__init__(f"{path}: {problem}")
        self.path = Path(path)
        self.problem = problem


def read_launch_text(path: Path) -> str:
    """The launch file's text; a missing, unreadable or non-UTF-8 file is one ``LaunchFileError``."""
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise LaunchFileError(path, "no such launch file") from None
    except IsADirectoryError:
        raise LaunchFileError(path, "is a folder, not a launch file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise LaunchFileError(path, f"cannot read it: {error}") from None
