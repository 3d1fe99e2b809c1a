"""The CLI's one error type: printed as one line, exit status 1, never a traceback."""

from __future__ import annotations

from shared_models.errors import SkydeckError

__all__ = ["CliError"]


class CliError(SkydeckError):
    """A problem the user can fix; the message says what happened and what to do."""
