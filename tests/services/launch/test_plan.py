"""From launch file and options to processes: ports, placeholders, order, exclusions."""

from __future__ import annotations

import sys

import pytest

import services.launch
from services.launch import (
    LaunchError,
    LaunchOptions,
    LaunchSpec,
    NodePlan,
    NodeSpec,
    core_url,
    default_command,
    default_launch_file,
    load_launch_file,
    plan_launch,
)


def _spec(*nodes: NodeSpec) -> LaunchSpec:
    return LaunchSpec(nodes=nodes)


def test_workshop_plan_with_defaults() -> None:
    plans = plan_launch(load_launch_file(default_launch_file(), {}), LaunchOptions(seed=42))
    assert [(plan.name, plan.port) for plan in plans] == [
        ("core", 8000),
        ("sim", 8001),
        ("perception", 8002),
        ("control", 8003),
        ("ai", 8004),
    ]
    assert plans[1].args == ("--speed", "1", "--seed", "42", "--boxes", "8")
    assert plans[0].is_core and not plans[1].is_core
    assert plans[1].url == "http://127.0.0.1:8001"


def test_options_fill_the_placeholders_and_shift_the_ports() -> None:
    spec = _spec(
        NodeSpec(
            name="sim",
            run="sim",
            port_offset=1,
            args=("--speed", "{speed}", "--boxes", "{boxes}", "--x={base_port}/{seed}"),
            env={"SKYDECK_SIM_SEED": "{seed}"},
        )
    )
    (plan,) = plan_launch(spec, LaunchOptions(base_port=9100, speed="max", seed=7, world_options={"boxes": 3}))
    assert plan.port == 9101
    assert plan.args == ("--speed", "max", "--boxes", "3", "--x=9100/7")
    assert plan.env == {"SKYDECK_SIM_SEED": "7"}


def test_literal_braces_survive() -> None:
    spec = _spec(NodeSpec(name="a", run="a.py", port_offset=0, args=('{{"k": {boxes}}}',)))
    assert plan_launch(spec, LaunchOptions(world_options={"boxes": 2}))[0].args == ('{"k": 2}',)


def test_the_core_starts_first_wherever_it_is_listed() -> None:
    spec = _spec(
        NodeSpec(name="sim", run="sim", port_offset=1),
        NodeSpec(name="hub", run="core", port_offset=5),
        NodeSpec(name="ai", run="ai", port_offset=4),
    )
    options = LaunchOptions(base_port=9000)
    assert [plan.name for plan in plan_launch(spec, options)] == ["hub", "sim", "ai"]
    assert core_url(spec, options) == "http://127.0.0.1:9005"


def test_without_a_core_the_core_url_is_the_base_port() -> None:
    spec = _spec(NodeSpec(name="sim", run="sim", port_offset=1))
    assert core_url(spec, LaunchOptions(base_port=9000)) == "http://127.0.0.1:9000"


def test_exclude_drops_nodes() -> None:
    spec = load_launch_file(default_launch_file(), {})
    plans = plan_launch(spec, LaunchOptions(seed=1, exclude=("ai", "perception")))
    assert [plan.name for plan in plans] == ["core", "sim", "control"]


def test_exclude_of_an_unknown_node_is_an_error() -> None:
    spec = load_launch_file(default_launch_file(), {})
    with pytest.raises(
        LaunchError,
        match=r"--exclude names 'planner', which the launch file does not have; its nodes are: core, sim,",
    ):
        plan_launch(spec, LaunchOptions(seed=1, exclude=("ai", "planner")))


def test_a_base_port_that_pushes_a_node_past_65535() -> None:
    spec = load_launch_file(default_launch_file(), {})
    with pytest.raises(LaunchError, match="puts the last node on port 65537"):
        plan_launch(spec, LaunchOptions(base_port=65533, seed=1))


def test_seed_placeholder_needs_a_seed() -> None:
    spec = _spec(NodeSpec(name="sim", run="sim", port_offset=1, args=("--seed", "{seed}")))
    with pytest.raises(LaunchError, match=r"'sim' uses \{seed\} but the options give it no value"):
        plan_launch(spec, LaunchOptions())
    drawn = LaunchOptions().with_seed()
    assert drawn.seed is not None
    assert plan_launch(spec, drawn)[0].args == ("--seed", str(drawn.seed))


def test_with_seed_keeps_a_given_seed() -> None:
    options = LaunchOptions(seed=5, exclude=("ai",))
    assert options.with_seed() is options
    drawn = LaunchOptions(base_port=9000, speed="2", world_options={"boxes": 4}, exclude=("ai",)).with_seed()
    assert (drawn.base_port, drawn.speed, drawn.world_options, drawn.exclude) == (9000, "2", {"boxes": 4}, ("ai",))


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"base_port": 0}, "--base-port must be a port number"),
        ({"base_port": 70000}, "--base-port must be a port number"),
        ({"speed": "fast"}, "--speed must be a positive number or 'max'"),
        ({"speed": "0"}, "--speed must be a positive number"),
        ({"speed": "nan"}, "--speed must be a positive number"),
        ({"seed": -1}, "--seed must be 0-"),
        ({"world_options": {"boxes": -1}}, "--boxes must be 0-30, got -1"),
        ({"world_options": {"boxes": 31}}, "--boxes must be 0-30, got 31"),
        ({"world_options": {"wheels": 3}}, "--wheels: no world has this option; theirs are boxes, robots, obstacles"),
    ],
)
def test_bad_options(options: dict[str, object], message: str) -> None:
    with pytest.raises(LaunchError, match=message):
        LaunchOptions(**options)  # type: ignore[arg-type]


def test_default_command_runs_the_cli() -> None:
    core = NodePlan(name="core", run="core", port=9000, is_core=True)
    sim = NodePlan(name="sim", run="sim", port=9001, args=("--seed", "3"))
    cli = [sys.executable, "-m", "services.cli"]
    assert default_command(core) == [*cli, "core", "--port", "9000"]
    assert default_command(sim) == [*cli, "run", "sim", "--port", "9001", "--seed", "3"]


def test_a_world_option_not_given_is_its_worlds_default() -> None:
    from sim_server.drone.limits import DEFAULT_BOXES
    from sim_server.robot.limits import DEFAULT_OBSTACLES

    values = LaunchOptions().placeholders()
    assert (values["boxes"], values["robots"], values["obstacles"]) == (str(DEFAULT_BOXES), "1", str(DEFAULT_OBSTACLES))


def test_public_api() -> None:
    assert sorted(services.launch.__all__) == sorted(
        [
            "BUILTIN_RUNS",
            "DEFAULT_BASE_PORT",
            "PLACEHOLDERS",
            "CommandFor",
            "LaunchArgument",
            "LaunchError",
            "LaunchFileError",
            "LaunchOptions",
            "LaunchSpec",
            "NodePlan",
            "NodeSpec",
            "NodeState",
            "NodeStatus",
            "RosLaunch",
            "RosNode",
            "Supervisor",
            "core_answers",
            "core_url",
            "default_command",
            "default_launch_file",
            "find_launch_file",
            "is_roslaunch_file",
            "launch_arguments",
            "package_launch_file",
            "load_launch_file",
            "load_roslaunch_file",
            "plan_launch",
            "run_launch",
            "shipped_launch_files",
            "show_arguments",
        ]
    )
    for name in services.launch.__all__:
        assert getattr(services.launch, name) is not None


def test_endpoint_ports_reach_the_core_as_its_flags() -> None:
    spec = load_launch_file(default_launch_file(), {})
    core, *nodes = plan_launch(spec, LaunchOptions(seed=1, endpoint_ports={"rosbridge": 0, "foxglove": 9876}))
    assert core.args[-4:] == ("--rosbridge-port", "0", "--foxglove-port", "9876")
    assert core.env == {} and all("--rosbridge-port" not in node.args for node in nodes)
    default_core, *_ = plan_launch(spec, LaunchOptions(seed=1))
    assert "--rosbridge-port" not in default_core.args  # at the default base port: the core's own setting


def test_endpoint_ports_move_with_the_base_port_unless_given() -> None:
    """Two launches side by side (issue 32): each core's endpoints move as far as its base port."""
    spec = load_launch_file(default_launch_file(), {})
    first, *_ = plan_launch(spec, LaunchOptions(seed=1, base_port=19340))
    second, *_ = plan_launch(spec, LaunchOptions(seed=1, base_port=19370))
    assert first.args[-4:] == ("--rosbridge-port", "20430", "--foxglove-port", "20105")
    assert second.args[-4:] == ("--rosbridge-port", "20460", "--foxglove-port", "20135")
    given, *_ = plan_launch(spec, LaunchOptions(seed=1, base_port=19340, endpoint_ports={"foxglove": 8765}))
    assert given.args[-4:] == ("--rosbridge-port", "20430", "--foxglove-port", "8765")
    options = LaunchOptions(base_port=19340).with_given_ports({"rosbridge": 0, "foxglove": 1})
    assert options.with_given_ports({"rosbridge": 5}).endpoint_ports == {"rosbridge": 0, "foxglove": 1}
    assert options.endpoints_notice() == "protocol endpoints foxglove :1"
    assert LaunchOptions(base_port=19340).endpoints_notice() == (
        "protocol endpoints rosbridge :20430, foxglove :20105 (moved with --base-port)"
    )
    assert LaunchOptions().endpoints_notice() == "protocol endpoints rosbridge :9090, foxglove :8765"


@pytest.mark.parametrize(
    ("options", "says"),
    [
        ({"endpoint_ports": {"rosbrige": 1}}, "no protocol endpoint 'rosbrige'"),
        ({"endpoint_ports": {"foxglove": 70000}}, "--foxglove-port must be a port number 0-65535"),
    ],
)
def test_bad_endpoint_ports_are_one_line(options: dict[str, object], says: str) -> None:
    with pytest.raises(LaunchError, match=says):
        LaunchOptions(**options)  # type: ignore[arg-type]


def test_an_endpoint_moved_past_65535_is_one_line_when_the_launch_starts_a_core() -> None:
    spec = load_launch_file(default_launch_file(), {})
    with pytest.raises(LaunchError, match="--base-port 65000 moves the rosbridge endpoint to port 66090, past 65535"):
        plan_launch(spec, LaunchOptions(seed=1, base_port=65000))
    given = LaunchOptions(seed=1, base_port=65000, endpoint_ports={"rosbridge": 0, "foxglove": 0})
    assert plan_launch(spec, given)[0].args[-4:] == ("--rosbridge-port", "0", "--foxglove-port", "0")
    joining = LaunchOptions(seed=1, base_port=65000, exclude=("core",))  # a running core: none planned
    assert [plan.name for plan in plan_launch(spec, joining)] == ["sim", "perception", "control", "ai"]

def test_ros2_adds_the_bridge_on_the_port_after_the_last() -> None:
    spec = load_launch_file(services.launch.find_launch_file("robot"))
    plans = plan_launch(spec, LaunchOptions(seed=1, base_port=9100, ros2=True))
    assert [(plan.name, plan.port) for plan in plans] == [("core", 9100), ("sim", 9101), ("ros2_bridge", 9102)]
    assert default_command(plans[-1])[-4:] == ["run", "ros2_bridge", "--port", "9102"]
    with pytest.raises(LaunchError, match="past 65535"):
        plan_launch(spec, LaunchOptions(seed=1, base_port=65534, ros2=True))
