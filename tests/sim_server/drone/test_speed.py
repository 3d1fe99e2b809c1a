"""``python -m sim_server.drone.speed``: a reading of the drone world and of the bare loop it is
compared with (the figures themselves belong to ``skydeck bench``; here only that both run)."""

from __future__ import annotations

import dataclasses
import math
import sys

import pytest

from sim_server.drone.limits import MAX_BOXES, PHYSICS_HZ
from sim_server.drone.speed import main, measure

pytestmark = pytest.mark.timeout(120)


def test_a_reading_has_both_rates_and_its_factors() -> None:
    reading = measure(boxes=2, steps=64, repeats=1)
    fields = dataclasses.asdict(reading)
    assert set(fields) == {"world_steps_per_s", "bare_steps_per_s"}
    assert all(math.isfinite(value) and value > 0 for value in fields.values()), fields
    assert reading.real_time_factor == reading.world_steps_per_s / PHYSICS_HZ
    assert reading.overhead == reading.bare_steps_per_s / reading.world_steps_per_s - 1.0


def test_the_command_prints_one_line(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(sys, "argv", ["speed", "--boxes", "2", "--steps", "64"])
    main()
    (line,) = capsys.readouterr().out.splitlines()
    assert line.startswith("world: ") and "x real time); bare stepSimulation loop: " in line and "overhead " in line


@pytest.mark.parametrize(
    ("argv", "wanted"),
    [
        (["--steps", "0"], "a whole number of at least 1, not '0'"),
        (["--steps", "many"], "a whole number of at least 1, not 'many'"),
        (["--boxes", "-1"], f"a whole number from 0 to {MAX_BOXES}, not '-1'"),
        (["--boxes", str(MAX_BOXES + 1)], f"a whole number from 0 to {MAX_BOXES}, not '{MAX_BOXES + 1}'"),
    ],
)
def test_a_count_out_of_range_is_one_line(
    argv: list[str], wanted: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(sys, "argv", ["speed", *argv])
    with pytest.raises(SystemExit) as ended:
        main()
    assert ended.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1] == f"speed: error: argument {argv[0]}: {wanted}"
