"""``--ros-args``: splitting them from a program's arguments, ``-p`` values read as YAML, params
files, node name patterns, and one clear error for what Skydeck cannot read."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.runtime import Node, NodeSettings
from services.runtime.parameters import InvalidParameterTypeException
from services.runtime.ros_args import (
    RosArguments,
    RosArgumentsError,
    parameter_value,
    parse_ros_args,
    rules_from_params_yaml,
    split_ros_args,
)


def test_split_keeps_the_programs_arguments() -> None:
    program, ros = split_ros_args(["--landing", "home", "--ros-args", "-p", "a:=1", "--", "--seed", "3"])
    assert program == ["--landing", "home", "--seed", "3"] and ros == ["-p", "a:=1"]
    assert split_ros_args(["x"]) == (["x"], [])


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("0.3", 0.3),
        ("3", 3),
        ("true", True),
        ("robot1", "robot1"),
        ("[1,2]", [1, 2]),
        ("[a, b]", ["a", "b"]),
        ("'0.3'", "0.3"),
        ("", ""),
        ("null", "null"),
        ("2024-01-01", "2024-01-01"),
    ],
)
def test_values_read_as_yaml_like_ros(text: str, value: object) -> None:
    assert parameter_value(text) == value
    assert type(parameter_value(text)) is type(value)


@pytest.mark.parametrize("text", ["{a: 1}", "[1, a]", "[[1]]"])
def test_values_that_are_no_parameter_are_refused(text: str) -> None:
    with pytest.raises(RosArgumentsError, match="not a parameter value"):
        parameter_value(text)


def test_p_for_every_node_or_one_and_later_wins() -> None:
    parsed = parse_ros_args(["-p", "speed:=0.3", "--param", "ai:speed:=0.9", "-p", "name:=robot1"])
    assert parsed.overrides_for("/ai") == {"speed": 0.9, "name": "robot1"}
    assert parsed.overrides_for("/control") == {"speed": 0.3, "name": "robot1"}


def test_params_file_with_nodes_wildcards_namespaces_and_nested_names(tmp_path: Path) -> None:
    path = tmp_path / "params.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    use_sim_time: true\n"
        "ai:\n  ros__parameters:\n    landing: home\n    gains: {p: 1.0, limits: {max: 2}}\n"
        "/robot1:\n  teleop:\n    ros__parameters:\n      speed: 0.2\n"
    )
    parsed = parse_ros_args(["--params-file", str(path), "-p", "ai:landing:=beside_last_box"])
    assert parsed.overrides_for("/ai") == {
        "use_sim_time": True, "landing": "beside_last_box", "gains.p": 1.0, "gains.limits.max": 2
    }
    assert parsed.overrides_for("/robot1/teleop") == {"use_sim_time": True, "speed": 0.2}
    assert parsed.overrides_for("/teleop") == {"use_sim_time": True}


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["-p"], "needs NAME:=VALUE"),
        (["-p", "speed"], "expected NAME:=VALUE"),
        (["-p", "x:={a: 1}"], "not a parameter value"),
        (["-r", "a:=b c"], "invalid name 'b c'"),
        (["-r", "scan"], "expected FROM:=TO"),
        (["-r", "__ns:=/robot 1"], "invalid name"),
        (["-r", "__node:=a/b"], "single token"),
        (["-r"], "needs FROM:=TO"),
        (["--log-level", "debug"], "--log-level is not supported"),
        (["--bogus"], "unknown ROS argument '--bogus'"),
        (["--params-file", "/nonexistent.yaml"], "cannot read it"),
    ],
)
def test_bad_ros_arguments_are_one_clear_error(args: list[str], message: str) -> None:
    with pytest.raises(RosArgumentsError, match=message) as raised:
        parse_ros_args(args)
    assert "\n" not in str(raised.value)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[1, 2]", "expected a mapping"),
        ("ai: 3", "expected {ros__parameters"),
        ("ai:\n  ros__parameters: [1]", "must be a mapping"),
        ("ai:\n  ros__parameters:\n    x: [1, a]", "parameter 'x'"),
        ("ai: [", "YAML syntax error at line 1"),
    ],
)
def test_bad_params_files_say_where(text: str, message: str) -> None:
    with pytest.raises(RosArgumentsError, match=message):
        rules_from_params_yaml(text)


def test_a_node_reads_its_cli_args_and_parameter_overrides() -> None:
    node = Node(
        "tuned", settings=NodeSettings(port=0), cli_args=["-p", "speed:=0.9", "-p", "use_sim_time:=true"],
        use_global_arguments=False,
    )
    assert node.declare_parameter("speed", 0.3).value == 0.9
    assert node.get_parameter("use_sim_time").value is True and node.get_clock().use_sim_time
    with pytest.raises(InvalidParameterTypeException, match="'speed'"):
        Node("tuned", settings=NodeSettings(port=0), cli_args=["-p", "speed:=fast"]).declare_parameter("speed", 0.3)


def test_arguments_add_up_in_order() -> None:
    combined = parse_ros_args(["-p", "a:=1"]) + parse_ros_args(["-p", "a:=2"])
    assert isinstance(combined, RosArguments) and combined.overrides_for("/n") == {"a": 2}
