"""Remapping and namespaces: ``-r FROM:=TO``, ``-r NODE:FROM:=TO``, ``__ns``, ``__node``, ROS 1's
bare ``name:=value`` arguments, and how a node's names resolve with them (the SDK's nodes too)."""

from __future__ import annotations

import pytest

from services.runtime import Node, NodeSettings
from services.runtime.ros_args import (
    NameResolver,
    RemapRule,
    RosArguments,
    RosArgumentsError,
    parse_ros1_args,
    parse_ros_args,
    set_process_ros_arguments,
)
from shared_models.geometry_msgs import Twist
from shared_models.std_srvs import Trigger


@pytest.fixture
def process_args():  # type: ignore[no-untyped-def]
    """Set this process's ROS arguments for one test, and put them back."""

    def set_args(*args: str) -> None:
        set_process_ros_arguments(parse_ros_args(list(args)))

    yield set_args
    set_process_ros_arguments(RosArguments())


def test_remap_rules_parse_with_an_optional_node() -> None:
    parsed = parse_ros_args(["-r", "scan:=/robot1/scan", "--remap", "estop:cmd_vel:=safe_cmd"])
    assert parsed.remap_rules == [
        RemapRule(None, "scan", "/robot1/scan"),
        RemapRule("estop", "cmd_vel", "safe_cmd"),
    ]
    assert parsed.remaps_for("estop") == [("scan", "/robot1/scan"), ("cmd_vel", "safe_cmd")]
    assert parsed.remaps_for("other") == [("scan", "/robot1/scan")]


def test_namespace_and_node_name_rules_later_wins_and_per_node() -> None:
    parsed = parse_ros_args(["-r", "__ns:=/robot1", "-r", "__node:=left", "-r", "talker:__ns:=/robot2"])
    assert parsed.namespace_for("talker") == "/robot2"
    assert parsed.namespace_for("listener") == "/robot1"
    assert parsed.node_name_for("listener") == "left"
    assert parsed.remaps_for("listener") == []  # __ns and __node are not name rules


def test_resolver_expands_relative_private_and_absolute_names() -> None:
    resolver = NameResolver("/robot1", "estop", [])
    assert resolver.full_node_name == "/robot1/estop"
    assert resolver.resolve("scan") == "/robot1/scan"
    assert resolver.resolve("/scan") == "/scan"
    assert resolver.resolve("~/state") == "/robot1/estop/state"
    assert resolver.resolve("~state") == "/robot1/estop/state"  # ROS 1's private form
    assert NameResolver("/", "talker", []).resolve("chatter") == "/chatter"


def test_resolver_applies_the_first_matching_rule_after_expansion() -> None:
    resolver = NameResolver("/robot1", "estop", [("scan", "base_scan"), ("/robot1/scan", "/never"), ("/odom", "/robot1/odom")])
    assert resolver.resolve("scan") == "/robot1/base_scan"  # the source expands in the namespace, so does the target
    assert resolver.resolve("/robot1/scan") == "/robot1/base_scan"
    assert resolver.resolve("/odom") == "/robot1/odom"
    assert resolver.resolve("odom") == "/robot1/odom"  # /robot1/odom: no rule for it
    assert resolver.resolve("bump") == "/robot1/bump"


def test_ros1_arguments_split_from_the_programs() -> None:
    program, parsed = parse_ros1_args(
        ["--fast", "chatter:=/news", "__name:=talker2", "__ns:=/robot1", "_rate:=5", "__master:=http://x:11311", "out.txt"]
    )
    assert program == ["--fast", "out.txt"]
    assert parsed.remaps_for("talker") == [("chatter", "/news")]
    assert parsed.node_name_for("talker") == "talker2"
    assert parsed.namespace_for("talker") == "/robot1"
    assert parsed.overrides_for("/robot1/talker2") == {"rate": 5}


def test_ros1_bad_argument_is_one_line() -> None:
    with pytest.raises(RosArgumentsError, match="_gains:=\\{a: 1\\}"):
        parse_ros1_args(["_gains:={a: 1}"])


def test_every_node_honours_the_process_remaps(process_args) -> None:  # type: ignore[no-untyped-def]
    process_args("-r", "cmd_vel:=/robot1/cmd_vel", "-r", "__ns:=/robot1", "-r", "estop:__node:=safety")
    node = Node("estop", settings=NodeSettings(port=0))
    node.create_publisher(Twist, "cmd_vel", 10)
    node.create_subscription(Twist, "scan", lambda msg: None, 10)
    node.create_service(Trigger, "~/reset", lambda request: Trigger.Response(success=True))
    assert node.get_name() == "/robot1/safety" and node.get_namespace() == "/robot1"
    description = node.describe()
    assert "/robot1/cmd_vel" in {e.name for e in description.publications}
    assert "/robot1/scan" in {e.name for e in description.subscriptions}
    services = {e.name for e in description.services}
    assert {"/robot1/safety/reset", "/robot1/safety/list_parameters"} <= services
    assert node.create_client(Trigger, "reset").srv_name == "/robot1/reset"


def test_namespace_keyword_and_cli_args_in_rclpys_form() -> None:
    node = Node(
        "talker", namespace="robot2", settings=NodeSettings(port=0), use_global_arguments=False,
        cli_args=["--ros-args", "-r", "chatter:=news", "-p", "rate:=2"],
    )  # fmt: skip
    assert node.get_name() == "/robot2/talker"
    assert node.resolve_topic_name("chatter") == "/robot2/news"
    assert node.declare_parameter("rate", 1).value == 2
