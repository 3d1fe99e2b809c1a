"""``python -m sim_server.robot.speed``: a reading of the robot world and of the bare loop it is
compared with (the figures themselves belong to ``skydeck bench``; here only that both run)."""

from __future__ import annotations

import dataclasses
import math
import sys

import pytest

from sim_server.robot.limits import MAX_CLASS_ROBOTS, PHYSICS_HZ, SCAN_EVERY_STEPS
from sim_server.robot.speed import main, measure


def test_a_reading_has_every_rate_of_both_loops_and_their_scans() -> None:
    reading = measure(robots=2, steps=2 * SCAN_EVERY_STEPS, repeats=2)
    fields = dataclasses.asdict(reading)
    assert set(fields) == {
        "world_steps_per_s", "bare_steps_per_s", "scan_ms", "bare_scan_ms", "world_steps_per_cpu_s", "bare_steps_per_cpu_s",
    }  # fmt: skip
    assert all(math.isfinite(value) and value > 0 for value in fields.values()), fields
    assert reading.real_time_factor == reading.world_steps_per_s / PHYSICS_HZ


def test_the_command_prints_one_line(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(sys, "argv", ["speed", "--steps", str(SCAN_EVERY_STEPS)])
    main()
    (line,) = capsys.readouterr().out.splitlines()
    assert line.startswith("robot world: ") and "bare loop: " in line and "per CPU second: world " in line


def test_a_robot_count_out_of_range_is_one_line(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(sys, "argv", ["speed", "--robots", "0"])
    with pytest.raises(SystemExit):
        main()
    assert capsys.readouterr().err.splitlines()[-1] == (
        f"speed: error: argument --robots: a whole number from 1 to {MAX_CLASS_ROBOTS}, not '0'"
    )
