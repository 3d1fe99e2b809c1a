"""Wrong launch files and wrong CLI arguments: one clear error line (plus argparse's usage where
argparse speaks), a non-zero exit status, never a traceback. Real `skydeck` subprocesses."""

from __future__ import annotations

import asyncio
import os
import sys
from pathlib import Path

import pytest

from tests.conftest import free_port

pytestmark = pytest.mark.timeout(90)

LAUNCH_FILES = {
    "syntax.yaml": ("nodes: [\n", "YAML syntax error at line 2"),
    "list.yaml": ("- 1\n", "expected a mapping with a `nodes:` list"),
    "unknown_field.yaml": ("nodes:\n  - name: x\n    run: core\n    port_offset: 0\n    bogus: 1\n", "nodes[0].bogus"),
    "bad_name.yaml": ("nodes:\n  - name: x y\n    run: core\n    port_offset: 0\n", "nodes[0].name"),
    "placeholder.yaml": (
        'nodes:\n  - name: x\n    run: core\n    port_offset: 0\n    args: ["{nope}"]\n', "unknown placeholder {nope}"
    ),
    "no_run.yaml": ("nodes:\n  - name: x\n    port_offset: 0\n", "nodes[0].run"),
    "negative_offset.yaml": ("nodes:\n  - name: x\n    run: core\n    port_offset: -1\n", "nodes[0].port_offset"),
    "empty.yaml": ("", "nodes"),
}

ARGUMENTS = [
    (["launch", "missing.yaml"], "no such launch file"),
    (["launch", "--speed", "0"], "--speed"),
    (["launch", "--boxes", "-3"], "--boxes"),
    (["launch", "--base-port", "0"], "port"),
    (["run", "sim", "--speed", "fast"], "--speed"),
    (["run", "sim", "--seed", "-1"], "--seed"),
    (["run", "sim", "--world", "robot", "--robots", "0"], "--robots"),
    (["run", "sim", "--world", "robot", "--robots", "-1"], "--robots"),
    (["run", "sim", "--world", "robot", "--robots", "two"], "--robots"),
    (["run", "sim", "--world", "robot", "--boxes", "3"], "--boxes"),
    (["launch", "robot", "--robots", "-1"], "--robots"),
    (["launch", "robot", "--obstacles", "9"], "--obstacles must be 0-8, got 9"),
    (["launch", "--obstacles", "2"], "--obstacles is the robot world's (`skydeck launch robot`)"),
    (["run", "sim", "--robots", "2"], "--robots (SKYDECK_SIM_ROBOTS) is the robot world's"),
    (["run", "sim", "--world", "moon"], "--world: no world 'moon': the worlds are drone, robot"),
    (["run", "no_such_node"], "no_such_node"),
    (["run", "missing.py"], "missing.py"),
    (["core", "--port", "70000"], "--port"),
    (["service", "call", "/control/fly", "{bad"], "not valid YAML or JSON"),
    (["topic", "pub", "/x", "geometry_msgs/msg/Nope", "{}"], "unknown interface"),
    (["topic", "echo", "/bad//name"], "invalid name"),
    (["frobnicate"], "invalid choice"),
    (["interface", "show", "nope/msg/Nothing"], "unknown interface"),
]


async def _skydeck(*args: str, cwd: Path) -> tuple[int, str]:
    env = {**os.environ, "SKYDECK_CORE_URL": f"http://127.0.0.1:{free_port()}"}
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", *args, env=env, cwd=cwd,
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
    )
    _, stderr = await asyncio.wait_for(process.communicate(), 60)
    return process.returncode or 0, stderr.decode()


def _check(args: list[str], status: int, stderr: str, fragment: str) -> None:
    assert "Traceback" not in stderr, (args, stderr)
    assert status != 0, args
    errors = [line for line in stderr.splitlines() if "error:" in line]
    assert len(errors) == 1, (args, stderr)
    others = [line for line in stderr.splitlines() if line and line not in errors]
    # argparse's usage, and the banner PyBullet's C code prints when the simulator imports it
    assert all(line.startswith(("usage:", " ", "pybullet build time")) for line in others), (args, stderr)
    assert fragment in errors[0], (args, errors[0])


async def test_wrong_launch_files_and_arguments_give_one_error_line(tmp_path: Path) -> None:
    cases: list[tuple[list[str], str]] = []
    for name, (text, fragment) in LAUNCH_FILES.items():
        (tmp_path / name).write_text(text)
        cases.append((["launch", str(tmp_path / name)], fragment))
    cases += ARGUMENTS
    results = await asyncio.gather(*(_skydeck(*args, cwd=tmp_path) for args, _ in cases))
    for (args, fragment), (status, stderr) in zip(cases, results, strict=True):
        _check(args, status, stderr, fragment)
    print(f"cli errors: {len(cases)} cases ({len(LAUNCH_FILES)} launch files)")
