"""The `skydeck` CLI as a user runs it: subprocesses against a real core and real nodes."""

from __future__ import annotations

import asyncio
import os
import sys

import pytest
import yaml

from services.runtime import Node
from shared_models.geometry_msgs import Point, PointStamped, Twist
from shared_models.std_msgs import Header
from shared_models.std_srvs import Trigger, TriggerResponse
from tests.conftest import free_port, wait_until


async def skydeck(core_url: str, *args: str, timeout_s: float = 20.0) -> tuple[int, str, str]:
    """Run `skydeck ARGS` against ``core_url``; returns (exit status, stdout, stderr)."""
    env = {**os.environ, "SKYDECK_CORE_URL": core_url}
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", *args, env=env,
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
    )
    stdout, stderr = await asyncio.wait_for(process.communicate(), timeout_s)
    assert b"Traceback" not in stderr, stderr.decode()
    return process.returncode or 0, stdout.decode(), stderr.decode()


class Talker(Node):
    def __init__(self, settings) -> None:
        super().__init__("talker", settings=settings)
        self.publisher = self.create_publisher(PointStamped, "/my_point", 10)
        self.create_timer(0.02, self.tick)
        self.create_service(Trigger, "/talker/ping", lambda request: TriggerResponse(success=True, message="pong"))
        self.twists: list[Twist] = []
        self.create_subscription(Twist, "/drone/cmd_vel", self.twists.append, 10)

    def tick(self) -> None:
        header = Header(stamp=self.get_clock().now().to_msg(), frame_id="odom")
        self.publisher.publish(PointStamped(header=header, point=Point(x=1.0, y=2.0, z=0.0)))


async def test_topic_list_info_echo_and_hz(core, start_node) -> None:
    await start_node(Talker)
    status, out, _ = await skydeck(core.url, "topic", "list", "-t")
    assert status == 0 and "/my_point [geometry_msgs/msg/PointStamped]" in out.splitlines()
    status, out, _ = await skydeck(core.url, "topic", "info", "/my_point")
    assert "Type: geometry_msgs/msg/PointStamped" in out and " * /talker (http://127.0.0.1:" in out
    status, out, _ = await skydeck(core.url, "topic", "echo", "/my_point", "--once")
    assert status == 0 and "frame_id: odom" in out and "x: 1.0" in out and out.rstrip().endswith("---")
    status, out, _ = await skydeck(core.url, "topic", "hz", "/my_point", "-n", "3")
    assert status == 0 and "average rate:" in out
    assert sum(line.startswith("average rate:") for line in out.splitlines()) == 3  # one per second, -n of them


async def test_topic_pub_once_reaches_subscriber(core, start_node) -> None:
    talker = await start_node(Talker)
    status, out, err = await skydeck(
        core.url, "topic", "pub", "--once", "/drone/cmd_vel", "geometry_msgs/msg/Twist", "{linear: {x: 0.5}}"
    )
    assert status == 0, err
    await wait_until(lambda: any(t.linear.x == 0.5 for t in talker.twists), what="the published Twist")


async def test_topic_pub_refuses_bad_data_in_one_line(core) -> None:
    status, _, err = await skydeck(core.url, "topic", "pub", "--once", "/x", "geometry_msgs/msg/Twist", "{linear: {x: fast}}")
    assert status == 1 and err.count("\n") == 1 and "linear.x" in err
    status, _, err = await skydeck(core.url, "topic", "pub", "/x", "geometry_msgs/msg/Twst", "{}")
    assert status == 1 and "did you mean geometry_msgs/msg/Twist" in err


async def test_service_list_info_and_call(core, start_node) -> None:
    await start_node(Talker)
    status, out, _ = await skydeck(core.url, "service", "list", "-t")
    assert "/talker/ping [std_srvs/srv/Trigger]" in out.splitlines()
    status, out, _ = await skydeck(core.url, "service", "info", "/talker/ping")
    assert "Node: /talker" in out and "Type: std_srvs/srv/Trigger" in out
    status, out, _ = await skydeck(core.url, "service", "call", "/talker/ping")
    assert status == 0 and "success: true" in out and "message: pong" in out
    status, _, err = await skydeck(core.url, "service", "call", "/talker/pong")
    assert status == 1 and "unknown service /talker/pong (did you mean /talker/ping?)" in err
    status, _, err = await skydeck(core.url, "service", "call", "/talker/ping", "{extra: 1}")
    assert status == 1 and "extra" in err and "422" in err


async def test_service_list_leads_with_the_commands_and_shows_skydeck_s_own_with_all(core, start_node) -> None:
    await start_node(Talker)
    status, out, _ = await skydeck(core.url, "service", "list")
    names = out.split()
    assert status == 0 and names[0] == "/talker/ping"
    assert names[1:] == sorted(names[1:]) and len(names[1:]) == 6
    assert all(name.startswith("/talker/") and "_parameter" in name for name in names[1:])
    assert not [name for name in names if name.startswith("/rosapi/")]
    status, out, _ = await skydeck(core.url, "service", "list", "--all", "-t")
    lines = out.splitlines()
    assert status == 0 and [line.split()[0] for line in lines[: len(names)]] == names
    # Skydeck's own after them: rosapi's and tf2_web_republisher's (for rosbridge clients)
    assert "/rosapi/topics [rosapi_msgs/srv/Topics]" in lines[len(names) :]
    assert "/republish_tfs [tf2_web_republisher/srv/RepublishTFs]" in lines[len(names) :]
    status, out, _ = await skydeck(core.url, "service", "list", "-a")
    assert out.split()[: len(names)] == names and len(out.split()) > len(names)


async def test_node_list_and_info_show_pid(core, start_node) -> None:
    await start_node(Talker)
    status, out, _ = await skydeck(core.url, "node", "list")
    assert "/talker" in out.splitlines()
    status, out, _ = await skydeck(core.url, "node", "info", "talker")
    assert f"Pid: {os.getpid()}" in out and " * /my_point [geometry_msgs/msg/PointStamped]" in out
    status, _, err = await skydeck(core.url, "node", "info", "/nobody")
    assert status == 1 and "skydeck node list" in err
    status, _, err = await skydeck(core.url, "node", "info", "bad name")
    assert status == 1 and err.startswith("skydeck: error:") and "'bad name'" in err and len(err.splitlines()) == 1


async def test_interface_proto_prints_a_default_message_as_yaml(core) -> None:
    status, out, _ = await skydeck(core.url, "interface", "proto", "geometry_msgs/msg/Twist")
    assert status == 0
    assert yaml.safe_load(out) == {"linear": {"x": 0.0, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}}


async def test_interface_show_prints_ros_text(core) -> None:
    status, out, _ = await skydeck(core.url, "interface", "show", "geometry_msgs/msg/PointStamped")
    assert status == 0
    assert "std_msgs/Header header\n\tuint32 seq\n\tbuiltin_interfaces/Time stamp\n\t\tint32 sec" in out
    status, out, _ = await skydeck(core.url, "interface", "list", "-s")
    assert "std_srvs/srv/Trigger" in out.splitlines() and "geometry_msgs/msg/Point" not in out
    status, _, err = await skydeck(core.url, "interface", "show", "nope/msg/Nothing")
    assert status == 1 and err.startswith("skydeck: error: unknown interface")


async def test_core_not_running_is_one_clear_line() -> None:
    url = f"http://127.0.0.1:{free_port()}"
    status, _, err = await skydeck(url, "topic", "list")
    assert status == 1 and err.count("\n") == 1
    assert f"cannot reach the core at {url}" in err and "skydeck core" in err


@pytest.mark.parametrize(
    "args",
    [["topic", "echo", "/bad//name"], ["run", "no_such_node"], ["run", "missing.py"], ["launch", "--base-port", "0"]],
)
async def test_bad_arguments_are_one_line(core, args) -> None:
    status, _, err = await skydeck(core.url, *args)
    assert status != 0 and err.strip().count("\n") <= 1 and "error" in err


async def test_node_on_a_taken_port_says_so_in_one_line(core) -> None:
    status, _, err = await skydeck(core.url, "run", "perception", "--port", str(core.port))
    assert status == 1 and "cannot listen on 127.0.0.1" in err and "pick --port" in err


async def test_bad_setting_in_the_environment_is_one_line(core, monkeypatch) -> None:
    monkeypatch.setenv("SKYDECK_PORT", "abc")
    status, _, err = await skydeck(core.url, "run", "perception")
    assert status == 1 and err.startswith("skydeck: error: SKYDECK_PORT:") and err.count("\n") == 1


async def test_topic_pub_once_reaches_a_subscriber_that_comes_a_moment_later(core, start_node) -> None:
    """The gateway's publication is latched and stays advertised 2 s after the last socket
    closes, so `pub --once` reaches a node that links after the command has exited."""
    status, _, err = await skydeck(
        core.url, "topic", "pub", "--once", "/drone/cmd_vel", "geometry_msgs/msg/Twist", "{linear: {x: 0.25}}"
    )
    assert status == 0, err
    talker = await start_node(Talker)
    await wait_until(lambda: any(t.linear.x == 0.25 for t in talker.twists), timeout_s=5, what="the latched Twist")


async def test_echo_into_a_reader_that_stops_ends_quietly(core, start_node) -> None:
    """`skydeck topic echo /x | head -2`: when the reader of our output goes, we stop, exit 0."""
    await start_node(Talker)
    read, write = os.pipe()
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "topic", "echo", "/my_point",
        env={**os.environ, "SKYDECK_CORE_URL": core.url}, stdout=write, stderr=asyncio.subprocess.PIPE,
    )  # fmt: skip
    os.close(write)
    with os.fdopen(read, "rb") as output:
        assert b"frame_id" in await asyncio.to_thread(output.read, 200)  # like `head`, then it goes
    _, stderr = await asyncio.wait_for(process.communicate(), 20)
    assert process.returncode == 0 and b"Traceback" not in stderr, stderr.decode()
