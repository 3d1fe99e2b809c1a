"""Drive the robot from the terminal's keyboard, as teleop_twist_keyboard does.

The keys are laid out as a compass around ``k`` (stop): ``i`` forward, ``,`` back, ``j`` and
``l`` turn on the spot, ``u`` ``o`` ``m`` ``.`` arcs; ``q``/``z`` scale both speeds up or down by
10%, ``w``/``x`` only the forward one, ``e``/``c`` only the turn rate; any other key stops. The
terminal is put in cbreak mode (keys arrive one by one, unechoed; Ctrl-C still quits) and put
back as it was on exit, whatever the exit. The last command is sent again ``repeat_rate`` times a
second, since the robot stops by itself half a second after its last command (ROS's
teleop_twist_keyboard only repeats when asked to).

    skydeck run teleop --ros-args -p speed:=0.2 -p turn:=1.0
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import sys
import termios
import tty
from typing import Any

from services.behaviours.robot import BehaviourError, RobotBehaviour, run_behaviour
from services.runtime import NodeSettings

__all__ = ["KEY_BINDINGS", "KeyboardTeleop", "main"]

# key -> (forward, turn) directions, as teleop_twist_keyboard's moveBindings (holonomic off).
KEY_BINDINGS: dict[str, tuple[int, int]] = {
    "i": (1, 0), "o": (1, -1), "j": (0, 1), "l": (0, -1),
    "u": (1, 1), ",": (-1, 0), ".": (-1, 1), "m": (-1, -1),
}  # fmt: skip
# key -> (forward speed factor, turn rate factor), as its speedBindings.
SPEED_BINDINGS: dict[str, tuple[float, float]] = {
    "q": (1.1, 1.1), "z": (0.9, 0.9), "w": (1.1, 1.0), "x": (0.9, 1.0), "e": (1.0, 1.1), "c": (1.0, 0.9),
}  # fmt: skip
HELP = """\
Reading from the keyboard and publishing to {topic}
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%
anything else : stop

CTRL-C to quit
"""


class KeyboardTeleop(RobotBehaviour):
    """``teleop``: keys in, Twists out; needs a terminal on standard input."""

    def __init__(self, namespace: str = "/", settings: NodeSettings | None = None, *, stdin_fd: int | None = None) -> None:
        super().__init__("teleop", namespace, settings)
        self.declare_parameter("speed", 0.2)  # m/s forward at full key
        self.declare_parameter("turn", 1.0)  # rad/s at full key
        self.declare_parameter("repeat_rate", 10.0)  # Hz: the last command, sent again
        self.speed = self.get_parameter("speed").value
        self.turn = self.get_parameter("turn").value
        self.direction = (0, 0)
        self._fd = sys.stdin.fileno() if stdin_fd is None else stdin_fd
        if not os.isatty(self._fd):
            raise BehaviourError("teleop reads keys from a terminal, and standard input is not one")
        self._saved: list[Any] | None = None
        self._since_sent_s = 0.0

    # -- the terminal ---------------------------------------------------------------------------

    async def start(self) -> None:
        self._saved = termios.tcgetattr(self._fd)
        tty.setcbreak(self._fd)
        try:
            await super().start()
            asyncio.get_running_loop().add_reader(self._fd, self._on_key)
            sys.stdout.write(HELP.format(topic=self.cmd_vel.topic_name) + self._status() + "\n")
            sys.stdout.flush()
        except BaseException:
            self._restore_terminal()
            raise

    async def stop(self) -> None:
        try:
            with contextlib.suppress(RuntimeError, ValueError):
                asyncio.get_running_loop().remove_reader(self._fd)
            if self.direction != (0, 0):
                self.drive(0.0, 0.0)  # never leave the robot on a last moving command
            await super().stop()
        finally:
            self._restore_terminal()

    def _restore_terminal(self) -> None:
        if self._saved is not None:
            with contextlib.suppress(termios.error, OSError):
                termios.tcsetattr(self._fd, termios.TCSADRAIN, self._saved)
            self._saved = None

    def _on_key(self) -> None:
        try:
            data = os.read(self._fd, 32).decode(errors="replace")
        except OSError:
            data = ""
        if not data:  # the terminal went away
            asyncio.get_running_loop().remove_reader(self._fd)
            self.destroy_node()
            return
        for key in data:
            self.press(key)

    # -- the keys -------------------------------------------------------------------------------

    def press(self, key: str) -> None:
        """What one key does (see the module's docstring); sends the command at once."""
        if key in KEY_BINDINGS:
            self.direction = KEY_BINDINGS[key]
        elif key in SPEED_BINDINGS:
            linear, angular = SPEED_BINDINGS[key]
            self.speed *= linear
            self.turn *= angular
            sys.stdout.write(self._status() + "\n")
            sys.stdout.flush()
        else:
            self.direction = (0, 0)
        self._send()

    def _status(self) -> str:
        return f"currently:\tspeed {self.speed:.2f}\tturn {self.turn:.2f}"

    def _send(self) -> None:
        forward, turn = self.direction
        self.drive(forward * self.speed, turn * self.turn)
        self._since_sent_s = 0.0

    def control(self) -> tuple[float, float] | None:
        """Repeat the last command at ``repeat_rate`` while moving; stay quiet when stopped."""
        self._since_sent_s += 1.0 / self.RATE_HZ
        rate = self.get_parameter("repeat_rate").value
        if self.direction == (0, 0) or rate <= 0 or self._since_sent_s < 1.0 / rate - 1e-9:
            return None
        self._since_sent_s = 0.0
        forward, turn = self.direction
        return forward * self.speed, turn * self.turn


def main(argv: list[str] | None = None) -> int:
    """``skydeck run teleop``."""
    return run_behaviour(KeyboardTeleop, argv, prog="teleop", description=__doc__.splitlines()[0])
