"""Checking a world's inputs: the one exception for bad pilot or driver input, and the check
every world's commands start with (a finite number).

A world checks a command before anything changes, so nothing non-finite or out of bounds ever
reaches the physics; each world adds its own bounds (the drone's arena, the robot's speeds).
"""

from __future__ import annotations

import math

from shared_models.errors import SkydeckError

__all__ = ["InvalidCommand", "finite_number"]


class InvalidCommand(SkydeckError, ValueError):
    """Raised for a command (a setpoint, a cmd_vel) that is not finite or is out of bounds.

    Carries the command name, the offending field and its value; the message names all three
    and the accepted range. The world's state is unchanged when this is raised.
    """

    def __init__(self, command: str, field: str, value: object, reason: str) -> None:
        self.command = command
        self.field = field
        self.value = value
        super().__init__(f"{command}: {field}={value!r} {reason}")


def finite_number(command: str, field: str, value: object) -> float:
    """``value`` as a float; InvalidCommand naming ``command`` and ``field`` if it is not one."""
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InvalidCommand(command, field, value, "is not a number") from None
    if isinstance(value, bool) or not math.isfinite(number):
        raise InvalidCommand(command, field, value, "is not a finite number")
    return number
