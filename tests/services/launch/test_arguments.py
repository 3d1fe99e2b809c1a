"""Launch arguments: a YAML launch file's `arguments:` filled from `name:=value`, refused when
undeclared or missing; `skydeck launch FILE --show-args` for YAML and roslaunch files; and a
real launch whose argument reaches its node."""

from __future__ import annotations

import asyncio
import os
import signal
import sys
import textwrap
from pathlib import Path

import httpx
import pytest

from services.launch import (
    LaunchFileError,
    LaunchOptions,
    launch_arguments,
    load_launch_file,
    plan_launch,
    run_launch,
    show_arguments,
)
from services.launch.background import BackgroundProcess
from tests.conftest import free_port_block
from tests.services.cli.test_cli import skydeck

pytestmark = [pytest.mark.timeout(30)]

LAUNCH = """\
arguments:
  rate:
    default: 30
    description: the control loop's rate, Hz
  world: {}
  verbose: {default: true}
nodes:
  - {name: core, run: core, port_offset: 0}
  - name: sim
    run: sim
    port_offset: 1
    args: ["--rate", "{rate}", "--world", "{world}", "--speed", "{speed}", "{{literal}}"]
    env: {VERBOSE: "{verbose}"}
"""


def _write(tmp_path: Path, text: str = LAUNCH, name: str = "launch.yaml") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def test_given_values_and_defaults_fill_the_placeholders(tmp_path: Path) -> None:
    spec = load_launch_file(_write(tmp_path), {"world": "w{1}"})
    sim = plan_launch(spec, LaunchOptions(speed="2", seed=1))[1]
    assert sim.args == ("--rate", "30", "--world", "w{1}", "--speed", "2", "{literal}")  # a value's braces stay text
    assert sim.env == {"VERBOSE": "true"}  # YAML's boolean, as the user wrote it
    spec = load_launch_file(_write(tmp_path), {"world": "robot", "rate": "5", "verbose": "false"})
    sim = plan_launch(spec, LaunchOptions(seed=1))[1]
    assert sim.args[:4] == ("--rate", "5", "--world", "robot") and sim.env == {"VERBOSE": "false"}


@pytest.mark.parametrize(
    ("given", "problem"),
    [
        ({"world": "x", "rat": "1"}, "rat:=1: no such launch argument (it takes rate, world, verbose: `--show-args` describes them)"),
        ({}, "launch argument 'world' has no default: give it as world:=VALUE"),
    ],
)
def test_an_undeclared_or_missing_argument_is_one_line(tmp_path: Path, given: dict[str, str], problem: str) -> None:
    path = _write(tmp_path)
    with pytest.raises(LaunchFileError) as caught:
        load_launch_file(path, given)
    assert str(caught.value) == f"{path}: {problem}"


def test_a_launch_file_without_arguments_refuses_any(tmp_path: Path) -> None:
    with pytest.raises(LaunchFileError, match=r"robot.yaml: x:=1: no such launch argument \(it declares none\)$"):
        run_launch("robot", launch_args={"x": "1"})


def test_an_argument_with_choices_takes_only_them(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        'arguments: {fast: {default: "false", choices: [true, false]}}\n'
        'nodes: [{name: sim, run: sim, port_offset: 1, args: ["--fast", "{fast}"]}]',
    )
    assert plan_launch(load_launch_file(path, {"fast": "true"}), LaunchOptions(seed=1))[0].args == ("--fast", "true")
    with pytest.raises(LaunchFileError, match=r"fast:=maybe: not one of its choices \(true, false\)$"):
        load_launch_file(path, {"fast": "maybe"})
    assert "        Valid choices are: ['true', 'false']\n        (default: 'false')" in show_arguments(launch_arguments(path))
    workshop = launch_arguments("workshop")["start_mission"]  # the AI waits unless told
    assert (workshop.default, workshop.choices) == ("false", ("true", "false"))


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ('arguments: {speed: {default: "2"}}\nnodes: [{name: sim, run: sim, port_offset: 1}]',
         "arguments: 'speed' is a launch option (--speed); choose another name"),
        ('arguments: {"my arg": {}}\nnodes: [{name: sim, run: sim, port_offset: 1}]', "arguments.my arg.[key]: String should match"),
        ("arguments: {a: {defualt: 1}}\nnodes: [{name: sim, run: sim, port_offset: 1}]",
         "arguments.a.defualt: unknown field (allowed: default, description, choices)"),
        ('arguments: {a: {default: "2", choices: ["0", "1"]}}\nnodes: [{name: sim, run: sim, port_offset: 1}]',
         "arguments.a: Value error, default '2' is not one of its choices (0, 1)"),
        ('arguments: {a: {}}\nnodes: [{name: sim, run: sim, port_offset: 1, args: ["{b}"]}]',
         "nodes[0].args[0]: unknown placeholder {b} in '{b}'; known: {speed}, {seed}, {boxes}, {robots}, {obstacles}, {base_port}, {a} "
         "(or declare it under `arguments:`)"),
    ],
)  # fmt: skip
def test_bad_declarations_are_one_line(tmp_path: Path, text: str, problem: str) -> None:
    path = _write(tmp_path, text)
    with pytest.raises(LaunchFileError) as caught:
        load_launch_file(path)
    assert caught.value.problem.startswith(problem) and "\n" not in str(caught.value)


def test_show_args_lists_yaml_and_roslaunch_arguments(tmp_path: Path) -> None:
    declared = launch_arguments(_write(tmp_path))  # a required argument is listed, not demanded
    assert show_arguments(declared) == textwrap.dedent(
        """\
        Arguments (pass arguments as '<name>:=<value>'):

            'rate':
                the control loop's rate, Hz
                (default: '30')

            'world':
                no description given
                (required)

            'verbose':
                no description given
                (default: 'true')"""
    )
    xml = tmp_path / "demo.launch"
    xml.write_text(
        '<launch>\n<arg name="use_sim_time" default="true" doc="run on /clock"/>\n<arg name="fixed" value="1"/>\n'
        '<group ns="r1"><arg name="robot" doc="which robot"/></group>\n'
        '<arg name="home" default="$(env HOME)"/>\n</launch>\n'
    )
    assert {name: (a.default, a.description) for name, a in launch_arguments(xml).items()} == {
        "use_sim_time": ("true", "run on /clock"),
        "robot": (None, "which robot"),
        "home": ("$(env HOME)", ""),  # as written: --show-args resolves nothing
    }
    assert show_arguments(launch_arguments("robot")).endswith("\n\n  No arguments.")


async def test_the_cli_shows_arguments_and_refuses_unknown_ones_in_one_line(tmp_path: Path) -> None:
    url = "http://127.0.0.1:9"  # neither needs a core
    status, out, _ = await skydeck(url, "launch", str(_write(tmp_path)), "--show-args")
    assert status == 0 and "    'world':\n        no description given\n        (required)" in out
    status, out, _ = await skydeck(url, "launch", "tests/ros/corpus/ros1/ros_workshop/launch/nodes.launch", "--show-args")
    assert status == 0 and "    'use_sim_time':" in out
    status, _, err = await skydeck(url, "launch", str(_write(tmp_path)), "world:=x", "--speed", "2", "nope:=1")
    assert status == 1 and err.count("\n") == 1 and "nope:=1: no such launch argument" in err
    status, _, err = await skydeck(url, "launch", "x:=1")  # no file: the default one's arguments
    assert status == 1 and err.count("\n") == 1 and "workshop.yaml: x:=1: no such launch argument (it takes start_mission" in err
    status, _, err = await skydeck(url, "launch", str(_write(tmp_path)), "world")
    assert status == 1 and "launch arguments are NAME:=VALUE" in err
    status, _, err = await skydeck(url, "launch", str(tmp_path / "none.yaml"), "--show-args")
    assert status == 1 and err.count("\n") == 1 and "none.yaml: no such launch file" in err


@pytest.mark.e2e
@pytest.mark.timeout(90)
async def test_an_argument_given_on_the_command_line_reaches_the_node(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        f"""\
        arguments:
          ns: {{default: first, description: the talker's namespace}}
        nodes:
          - {{name: core, run: core, port_offset: 0}}
          - name: talker
            run: {Path("examples/send_message.py").resolve()}
            port_offset: 1
            args: ["--ros-args", "-r", "__ns:=/{{ns}}"]
        """,
    )
    base = free_port_block(2)
    launch = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "launch", str(path), "--base-port", str(base),
         "--rosbridge-port", "0", "--foxglove-port", "0", "ns:=robot7"],  # after the options, as roslaunch takes them
        name="launch", env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    try:
        await launch.await_line("[launch] all 2 nodes up", 60)
        async with httpx.AsyncClient() as http:
            graph = (await http.get(f"http://127.0.0.1:{base}/api/graph", timeout=5)).json()
        names = {node["name"] for node in graph["nodes"]}
        assert "/robot7/send_message_node" in names and "/first/send_message_node" not in names, names
    finally:
        assert await asyncio.to_thread(launch.stop, signal.SIGINT, 30)
    assert not any("Traceback" in line for line in launch.lines), launch.tail()
