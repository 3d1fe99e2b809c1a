"""What goes wrong with interface definition files, each said in one line.

    SkydeckError
    ├── DefinitionError (ValueError)      a .msg/.srv/.action file that cannot be read:
    │                                     ``my_pkg/msg/Bad.msg:3: unknown type 'flaot64' ...``
    └── DefinitionConflict (ValueError)   a type already known with other fields (a node sent
                                          the core another version of ``my_pkg/msg/Status``)
"""

from __future__ import annotations

from shared_models.close_codes import Close
from shared_models.errors import SkydeckError

__all__ = ["DefinitionConflict", "DefinitionError"]


class DefinitionError(SkydeckError, ValueError):
    """A definition file that cannot be read; the message begins with ``FILE:LINE:``."""

    http_status = 422
    close_code = Close.POLICY

    def __init__(self, origin: str, line: int | None, problem: str) -> None:
        where = f"{origin}:{line}" if line else origin
        super().__init__(f"{where}: {problem}")
        self.origin = origin
        self.line = line
        self.problem = problem


class DefinitionConflict(SkydeckError, ValueError):
    """A definition of a type this process already knows with other fields or constants."""

    http_status = 409
    close_code = Close.POLICY
