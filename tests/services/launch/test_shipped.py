"""The shipped launch files by name (`skydeck launch robot`), and the robot world's options."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from services.launch import (
    LaunchError,
    LaunchFileError,
    LaunchOptions,
    default_launch_file,
    find_launch_file,
    load_launch_file,
    plan_launch,
    shipped_launch_files,
)
from sim_server.robot.limits import MAX_ROBOTS

ROOT = Path(__file__).resolve().parents[3]


def test_the_shipped_launches_are_the_workshop_and_the_robot_world() -> None:
    shipped = shipped_launch_files()
    assert {"workshop", "robot"} <= set(shipped)
    assert shipped["workshop"] == default_launch_file()
    for path in shipped.values():
        load_launch_file(path)  # every shipped file is a valid launch


def test_a_bare_name_is_a_shipped_launch_and_anything_else_a_path(tmp_path: Path) -> None:
    assert find_launch_file(None) == default_launch_file()
    assert find_launch_file("robot") == shipped_launch_files()["robot"]
    mine = tmp_path / "robot.yaml"
    assert find_launch_file(str(mine)) == mine  # a path, even one named like a shipped launch
    with pytest.raises(LaunchFileError, match=r"no shipped launch of that name \(shipped: .*robot"):
        find_launch_file("robt")


def test_the_robot_launch_runs_the_core_and_the_robot_world() -> None:
    spec = load_launch_file(find_launch_file("robot"))
    plans = plan_launch(spec, LaunchOptions(seed=3, world_options={"robots": 2}, speed="max"))
    assert [(plan.name, plan.run) for plan in plans] == [("core", "core"), ("sim", "sim")]
    assert plans[1].args == ("--world", "robot", "--speed", "max", "--seed", "3", "--robots", "2", "--obstacles", "4")
    default = plan_launch(spec, LaunchOptions(seed=3))[1]
    assert default.args[-4:] == ("--robots", "1", "--obstacles", "4")


@pytest.mark.parametrize("robots", [0, -1, MAX_ROBOTS + 1])
def test_a_robot_count_out_of_range_is_refused(robots: int) -> None:
    with pytest.raises(LaunchError, match=f"--robots must be 1-{MAX_ROBOTS}, got {robots}"):
        LaunchOptions(world_options={"robots": robots})


def test_an_option_the_launch_file_does_not_use_is_refused() -> None:
    workshop = load_launch_file(default_launch_file(), {})
    robot = load_launch_file(find_launch_file("robot"))
    with pytest.raises(LaunchError, match=r"--robots 2: this launch file does not use it.*skydeck launch robot"):
        plan_launch(workshop, LaunchOptions(seed=1, world_options={"robots": 2}))
    with pytest.raises(LaunchError, match=r"--boxes 3: this launch file does not use it"):
        plan_launch(robot, LaunchOptions(seed=1, world_options={"boxes": 3}))


def test_the_cli_says_one_line_for_a_bad_robot_count() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "services.cli", "launch", "robot", "--robots", "0"],
        cwd=ROOT, capture_output=True, text=True, timeout=30,
    )  # fmt: skip
    assert result.returncode != 0
    assert result.stderr.strip().splitlines() == [f"skydeck: error: --robots must be 1-{MAX_ROBOTS}, got 0"]
