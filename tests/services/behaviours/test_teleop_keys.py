"""teleop's keys, in-process on a pseudo-terminal (no simulator): every direction of
teleop_twist_keyboard's compass, the speed keys, stop on anything else, and the repeat."""

from __future__ import annotations

import os
import pty
from collections.abc import Iterator

import pytest

from services.behaviours.teleop import KeyboardTeleop


@pytest.fixture
def teleop() -> Iterator[tuple[KeyboardTeleop, list[tuple[float, float]]]]:
    leader, follower = pty.openpty()
    node = KeyboardTeleop(stdin_fd=follower)
    sent: list[tuple[float, float]] = []
    node.drive = lambda linear, angular: sent.append((round(linear, 3), round(angular, 3)))  # type: ignore[method-assign]
    yield node, sent
    node.destroy_node()
    os.close(leader)
    os.close(follower)


def test_each_key_drives_its_way_at_once(teleop) -> None:  # type: ignore[no-untyped-def]
    node, sent = teleop
    expected = {
        "i": (0.2, 0.0), ",": (-0.2, 0.0),  # forward, back
        "j": (0.0, 1.0), "l": (0.0, -1.0),  # turn left, right on the spot
        "u": (0.2, 1.0), "o": (0.2, -1.0), "m": (-0.2, -1.0), ".": (-0.2, 1.0),  # arcs
        "k": (0.0, 0.0), "?": (0.0, 0.0),  # stop, and any other key stops
    }  # fmt: skip
    for key, command in expected.items():
        sent.clear()
        node.press(key)
        assert sent == [command], key


def test_speed_keys_scale_the_next_commands(teleop, capsys) -> None:  # type: ignore[no-untyped-def]
    node, sent = teleop
    node.press("i")
    for key in "qq":  # both 10% up, twice
        node.press(key)
    assert sent[-1] == (pytest.approx(0.242), 0.0)
    node.press("z")  # both 10% down
    node.press("x")  # forward only, down
    node.press("e")  # turn only, up
    node.press("j")
    assert sent[-1] == (0.0, pytest.approx(1.0 * 1.1 * 1.1 * 0.9 * 1.1, abs=1e-3))
    node.press("w")  # forward only, up
    node.press("c")  # turn only, down
    node.press("u")
    assert sent[-1] == (pytest.approx(0.2 * 1.21 * 0.9 * 0.9 * 1.1, abs=1e-3), pytest.approx(1.21 * 0.9 * 1.1 * 0.9, abs=1e-3))
    assert "currently:\tspeed 0.24\tturn 1.21" in capsys.readouterr().out


def test_the_last_command_repeats_while_moving_and_not_when_stopped(teleop) -> None:  # type: ignore[no-untyped-def]
    node, _ = teleop
    ticks = round(node.RATE_HZ / node.get_parameter("repeat_rate").value)
    node.press("u")
    repeats = [node.control() for _ in range(3 * ticks)]
    assert [c for c in repeats if c is not None] == [(0.2, 1.0)] * 3  # repeat_rate a second
    node.press("k")
    assert all(node.control() is None for _ in range(3 * ticks))
