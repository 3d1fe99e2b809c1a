"""``skydeck param`` and ``skydeck run ... --ros-args`` as a user runs them: subprocesses against a
real core and real nodes."""

from __future__ import annotations

import asyncio
import os
import signal
import sys
from pathlib import Path

import pytest
import yaml

from tests.conftest import wait_until
from tests.services.cli.test_cli import skydeck
from tests.services.cli.tuned_node import TunedNode

NODE_FILE = Path(__file__).with_name("tuned_node.py")


async def test_list_get_set_and_describe(core, start_node) -> None:
    node = await start_node(TunedNode)
    status, out, _ = await skydeck(core.url, "param", "list")
    assert status == 0 and out.splitlines()[:2] == ["/tuned:", "  flags"]
    status, out, _ = await skydeck(core.url, "param", "list", "tuned", "-t")
    assert out.splitlines() == [
        "  flags (type: integer array)",
        "  frozen (type: integer)",
        "  gains.p (type: double)",
        "  robot (type: string)",
        "  speed (type: double)",
        "  use_sim_time (type: boolean)",
    ]
    status, out, _ = await skydeck(core.url, "param", "list", "/tuned", "--param-prefixes", "gains")
    assert out.splitlines() == ["  gains.p"]
    status, out, _ = await skydeck(core.url, "param", "get", "/tuned", "speed")
    assert status == 0 and out.strip() == "Double value is: 0.3"
    status, out, _ = await skydeck(core.url, "param", "get", "/tuned", "flags")
    assert out.strip() == "Integer values are: [1, 2]"
    status, out, _ = await skydeck(core.url, "param", "set", "/tuned", "speed", "1")  # an integer for a double
    assert status == 0 and out.strip() == "Set parameter successful" and node.get_parameter("speed").value == 1.0
    status, out, _ = await skydeck(core.url, "param", "get", "/tuned", "speed", "--hide-type")
    assert out.strip() == "1.0"
    status, out, _ = await skydeck(core.url, "param", "describe", "/tuned", "speed", "frozen")
    assert "Parameter name: speed\n  Type: double\n  Description: m/s\n  Constraints:\n    Min value: 0.0\n    Max value: 2.0" in out
    assert "Read only: true" in out


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["set", "/tuned", "robot", "evil"], "setting parameter failed: no evil robots here"),
        (["set", "/tuned", "frozen", "8"], "setting parameter failed: parameter 'frozen' is read-only"),
        (["set", "/tuned", "speed", "fast"], "is of type double; got string 'fast'"),
        (["set", "/tuned", "speed", "3.0"], "outside its range [0.0, 2.0]"),
        (["set", "/tuned", "ghost", "1"], "'ghost' not declared by /tuned"),
        (["set", "/tuned", "speed", "{a: 1}"], "not a parameter value"),
        (["get", "/tuned", "ghost"], "/tuned has no value for parameter 'ghost'"),
        (["get", "/nobody", "speed"], "no node /nobody with parameters"),
        (["get", "bad name", "speed"], "'bad name'"),
    ],
)
async def test_refusals_print_the_reason_in_one_line_and_exit_1(core, start_node, args, message) -> None:
    node = await start_node(TunedNode)
    status, _, err = await skydeck(core.url, "param", *args)
    assert status == 1 and err.startswith("skydeck: error:") and err.count("\n") == 1, err
    assert message in err
    assert node.get_parameter("robot").value == "robot1" and node.get_parameter("speed").value == 0.3


async def test_dump_and_load_round_trip(core, start_node, tmp_path) -> None:
    node = await start_node(TunedNode)
    status, out, _ = await skydeck(core.url, "param", "dump", "/tuned")
    dumped = yaml.safe_load(out)
    assert status == 0 and dumped == {
        "/tuned": {
            "ros__parameters": {
                "flags": [1, 2], "frozen": 7, "gains": {"p": 1.0}, "robot": "robot1", "speed": 0.3, "use_sim_time": False
            }
        }
    }
    dumped["/tuned"]["ros__parameters"]["speed"] = 0.7
    dumped["/tuned"]["ros__parameters"]["gains"]["p"] = 2.5
    path = tmp_path / "tuned.yaml"
    path.write_text(yaml.safe_dump(dumped))
    status, out, err = await skydeck(core.url, "param", "load", "/tuned", str(path))
    assert status == 0, err
    assert "Parameter frozen is read-only and unchanged: skipped" in out and "Set parameter speed successful" in out
    assert node.get_parameter("speed").value == 0.7 and node.get_parameter("gains.p").value == 2.5
    path.write_text("/**:\n  ros__parameters:\n    robot: evil\n    speed: 1.0\n")
    status, out, err = await skydeck(core.url, "param", "load", "/tuned", str(path))
    assert status == 1 and "Set parameter robot failed: no evil robots here" in out and "Set parameter speed successful" in out
    assert "1 of 2 parameters were refused by /tuned" in err
    path.write_text("/other:\n  ros__parameters:\n    speed: 1.0\n")
    status, _, err = await skydeck(core.url, "param", "load", "/tuned", str(path))
    assert status == 1 and "has no parameters for /tuned" in err


async def _run_node(core_url: str, *args: str) -> asyncio.subprocess.Process:
    return await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "run", str(NODE_FILE), *args,
        env={**os.environ, "SKYDECK_CORE_URL": core_url},
        stdout=asyncio.subprocess.DEVNULL, stderr=asyncio.subprocess.PIPE,
    )


async def test_ros_args_override_the_defaults(core, tmp_path) -> None:
    params = tmp_path / "params.yaml"
    params.write_text("/tuned:\n  ros__parameters:\n    gains:\n      p: 4.0\n    robot: from_file\n")
    process = await _run_node(
        core.url, "--ros-args", "--params-file", str(params), "-p", "speed:=0.9", "-p", "robot:=r2", "-p", "flags:=[3,4,5]"
    )
    try:
        await wait_until(lambda: "/tuned" in core.registry.nodes, timeout_s=20, what="the node to register")
        status, out, _ = await skydeck(core.url, "param", "dump", "/tuned")
        values = yaml.safe_load(out)["/tuned"]["ros__parameters"]
        assert (values["speed"], values["robot"], values["flags"], values["gains"]["p"]) == (0.9, "r2", [3, 4, 5], 4.0)
    finally:
        process.send_signal(signal.SIGINT)
        _, stderr = await asyncio.wait_for(process.communicate(), 15)
    assert b"Traceback" not in stderr


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["-p", "speed:=fast"], "/tuned: parameter 'speed' is of type double; got string 'fast'"),
        (["-p", "speed:=5.0"], "/tuned: parameter 'speed' = 5.0 is outside its range"),
        (["-p", "frozen:=[1, a]"], "not a parameter value"),
        (["-r", "scan:=/robot 1/scan"], "-r scan:=/robot 1/scan: invalid name"),
    ],
)
async def test_bad_ros_args_stop_the_node_with_one_line(core, args, message) -> None:
    process = await _run_node(core.url, "--ros-args", *args)
    _, stderr = await asyncio.wait_for(process.communicate(), 20)
    err = stderr.decode()
    assert process.returncode == 1 and message in err and err.count("\n") == 1, err
