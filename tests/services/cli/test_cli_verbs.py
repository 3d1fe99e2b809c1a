"""The verbs ROS users type beyond list/info/echo/pub, as subprocesses against a real core."""

from __future__ import annotations

import asyncio
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from services.runtime import Node
from shared_models.geometry_msgs import Point, PointStamped
from shared_models.sensor_msgs import CompressedImage, LaserScan
from shared_models.std_msgs import Header, String
from shared_models.std_srvs import SetBool, SetBoolResponse, Trigger, TriggerResponse
from tests.conftest import free_port, wait_until
from tests.services.cli.test_cli import skydeck


class Stamped(Node):
    """Stamped points at 50 Hz, a scan, a string, a subscriber, and services of different types
    (one that never answers)."""

    def __init__(self, settings) -> None:
        super().__init__("stamped", settings=settings)
        self.points = self.create_publisher(PointStamped, "/stamped", 10)
        self.scans = self.create_publisher(LaserScan, "/scan", 10)
        self.text = self.create_publisher(String, "/text", 10)
        self.create_timer(0.02, self.tick)
        self.create_service(Trigger, "/stamped/ping", lambda request: TriggerResponse(success=True))
        self.create_service(SetBool, "/stamped/enable", lambda request: SetBoolResponse(success=True))
        self.create_service(Trigger, "/stamped/stall", self.stall)
        self.heard: list[String] = []
        self.create_subscription(String, "/heard", self.heard.append, 10)

    async def stall(self, request: Trigger.Request) -> TriggerResponse:
        await asyncio.Event().wait()  # never answers: the caller's --timeout ends the call
        return TriggerResponse()

    def tick(self) -> None:
        header = Header(stamp=self.get_clock().now().to_msg(), frame_id="odom")
        self.points.publish(PointStamped(header=header, point=Point(x=1.5, y=-2.0)))
        self.scans.publish(LaserScan(header=header, ranges=[1.0, 2.0, 3.0], angle_max=6.2))
        self.text.publish(String(data="a, b"))


async def test_topic_type_and_find(core, start_node) -> None:
    await start_node(Stamped)
    assert await skydeck(core.url, "topic", "type", "/stamped") == (0, "geometry_msgs/msg/PointStamped\n", "")
    status, out, _ = await skydeck(core.url, "topic", "find", "sensor_msgs/msg/LaserScan")
    assert status == 0 and out.splitlines() == ["/scan"]
    status, _, err = await skydeck(core.url, "topic", "type", "/nope")
    assert status == 1 and "unknown topic /nope" in err and err.count("\n") == 1
    status, _, err = await skydeck(core.url, "topic", "find", "sensor_msgs/msg/LaserScn")
    assert status == 1 and "did you mean sensor_msgs/msg/LaserScan" in err
    status, _, err = await skydeck(core.url, "topic", "find", "std_srvs/srv/Trigger")
    assert status == 1 and "service find" in err


async def test_echo_field_csv_no_arr_and_qos_depth(core, start_node) -> None:
    await start_node(Stamped)
    status, out, _ = await skydeck(core.url, "topic", "echo", "/stamped", "--field", "point.x", "-n", "2")
    assert status == 0 and out.splitlines()[-4:] == ["1.5", "---", "1.5", "---"]
    status, out, _ = await skydeck(core.url, "topic", "echo", "/scan", "--field", "ranges[1]", "--once")
    assert out.splitlines()[-2:] == ["2.0", "---"]
    status, out, _ = await skydeck(core.url, "topic", "echo", "/stamped", "--field", "point", "--csv", "--once", "--qos-depth", "5")
    assert status == 0 and out.splitlines()[-1] == "1.5,-2.0,0.0"
    status, out, _ = await skydeck(core.url, "topic", "echo", "/text", "--csv", "--once")
    assert out.splitlines()[-1] == '"a, b"'
    status, out, _ = await skydeck(core.url, "topic", "echo", "/scan", "--no-arr", "--once")
    scan = yaml.safe_load(out.split("---")[0].split("\n", 1)[1] if out.startswith("WARNING") else out.split("---")[0])
    assert scan["ranges"] == "<array, length: 3>" and scan["angle_max"] == pytest.approx(6.2)
    status, out, _ = await skydeck(core.url, "topic", "echo", "/scan", "--field", "header", "--json", "--once")
    assert json.loads(out.splitlines()[-1])["frame_id"] == "odom"
    status, _, err = await skydeck(core.url, "topic", "echo", "/stamped", "--field", "point.w", "--once")
    assert status == 1 and "the message has no point.w" in err and err.count("\n") == 1
    status, _, err = await skydeck(core.url, "topic", "echo", "/stamped", "--qos-depth", "0")
    assert status == 2 and "positive integer" in err


async def test_echo_rate_and_timeout(core, start_node) -> None:
    await start_node(Stamped)
    status, out, _ = await skydeck(core.url, "topic", "echo", "/stamped", "--rate", "5", "-n", "3", "--json")
    seqs = [json.loads(line)["header"]["seq"] for line in out.splitlines() if line.startswith("{")]
    # At most 5 a second of a 50 Hz topic, the newest winning: messages are skipped (without
    # --rate the stream's queue gives every one, seq by seq).
    assert status == 0 and len(seqs) == 3 and seqs[-1] - seqs[0] > 2, seqs
    status, out, err = await skydeck(core.url, "topic", "echo", "/silent", "--timeout", "0.5")
    assert status == 1 and err == "skydeck: error: no message on /silent within 0.5 s\n"
    assert "WARNING: topic [/silent] does not appear to be published yet" in out


async def test_pub_times_at_a_rate(core, start_node) -> None:
    stamped = await start_node(Stamped)
    status, out, err = await skydeck(core.url, "topic", "pub", "/heard", "std_msgs/msg/String", "{data: hi}", "-r", "20", "-t", "3")
    # It exits (at 20 Hz without -t it would publish until Ctrl-C); the subscriber links to the
    # new publication while it runs, so it hears some of the three, the last one latched.
    assert status == 0 and "publishing #1: String(" in out, err
    await wait_until(lambda: bool(stamped.heard), what="the published strings")
    assert {message.data for message in stamped.heard} == {"hi"}


async def test_service_call_timeout_and_interface_list_of_messages(core, start_node) -> None:
    await start_node(Stamped)
    status, _, err = await skydeck(core.url, "service", "call", "/stamped/stall", "--timeout", "0.5")
    assert status == 1 and err == "skydeck: error: no answer from /stamped/stall within 0.5 s (--timeout to wait longer)\n"
    status, out, _ = await skydeck(core.url, "interface", "list", "--only-msgs")
    names = out.splitlines()
    assert status == 0 and "geometry_msgs/msg/Point" in names and not any("/srv/" in name for name in names)
    status, out, _ = await skydeck(core.url, "interface", "list", "-m")
    assert out.splitlines() == names


@pytest.mark.parametrize(
    ("args", "error"),
    [
        (["topic", "info", "/nope"], "unknown topic /nope: see `skydeck topic list`"),
        (["topic", "pub", "--once", "/stamped", "std_msgs/msg/String", "{data: x}"],
         "/stamped is geometry_msgs/msg/PointStamped, not std_msgs/msg/String"),
        (["topic", "pub", "--once", "/heard", "std_srvs/srv/Trigger"], "std_srvs/srv/Trigger is a service type: use `skydeck service call`"),
        (["topic", "hz", "/bad//name"], "invalid"),
        (["service", "info", "/nope"], "unknown service /nope: see `skydeck service list`"),
        (["service", "call", "/stamped/enable", "{data: maybe}"], "data"),
        (["node", "kill", "/nobody"], "unknown node /nobody: see `skydeck node list`"),
        (["node", "info", "bad name"], "'bad name'"),
        (["interface", "proto", "nope/msg/Nothing"], "unknown interface"),
        (["launch", "--show-args", "no_such_launch"], "no such launch file"),
        (["completion", "fish"], "invalid choice: 'fish'"),
        (["bench", "--out", "pyproject.toml/bench/results.json"], "cannot write pyproject.toml/bench/results.json: "),
        (["bench", "--out", "tests"], "cannot write tests: it is a folder"),
    ],
)  # fmt: skip
async def test_bad_input_is_one_error_line_and_a_non_zero_status(core, start_node, args, error) -> None:
    await start_node(Stamped)
    status, _, err = await skydeck(core.url, *args)
    errors = [line for line in err.splitlines() if "error:" in line]
    assert status != 0 and len(errors) == 1 and error in errors[0], err
    assert all(line == errors[0] or line.startswith(("usage:", " ")) for line in err.splitlines()), err  # argparse's usage


async def test_hz_window_bw_and_delay(core, start_node) -> None:
    await start_node(Stamped)
    status, out, _ = await skydeck(core.url, "topic", "hz", "/stamped", "--window", "5", "-n", "2")
    assert status == 0 and out.count("average rate:") == 2 and "window: 5" in out
    status, out, _ = await skydeck(core.url, "topic", "bw", "/stamped", "-w", "20", "-n", "1")
    assert status == 0 and "KB/s from 20 messages" in out and "Message size mean:" in out
    status, out, _ = await skydeck(core.url, "topic", "delay", "/stamped", "-n", "1", "--window", "10")
    delay = float(next(line for line in out.splitlines() if line.startswith("average delay:")).split(":")[1])
    assert status == 0 and 0 <= delay < 1.0 and "window: 10" in out  # wall-clock stamps, one machine
    status, _, err = await skydeck(core.url, "topic", "delay", "/text", "-n", "1")
    assert status == 1 and "/text has no header.stamp" in err and err.count("\n") == 1


class Jpegs(Node):
    """A 3,000-byte CompressedImage at 50 Hz: 3.1 KB in msgpack, 4.1 KB as JSON (base64)."""

    def __init__(self, settings) -> None:
        super().__init__("jpegs", settings=settings)
        self.images = self.create_publisher(CompressedImage, "/jpegs", 10)
        self.create_timer(0.02, self.tick)

    def tick(self) -> None:
        header = Header(stamp=self.get_clock().now().to_msg(), frame_id="camera")
        self.images.publish(CompressedImage(header=header, format="jpeg", data=bytes(3000)))


async def test_hz_bw_and_delay_read_msgpack(core, start_node) -> None:
    # bw counts the frames it reads: msgpack's size (bytes as bytes), not the JSON's base64.
    await start_node(Jpegs)
    status, out, _ = await skydeck(core.url, "topic", "bw", "/jpegs", "-w", "10", "-n", "1")
    assert status == 0 and "Message size mean: 3.08 KB" in out, out
    status, out, _ = await skydeck(core.url, "topic", "delay", "/jpegs", "-w", "10", "-n", "1")
    assert status == 0 and "average delay:" in out, out


async def test_delay_on_sim_time_compares_with_clock(core, start_node) -> None:
    from shared_models.builtin_interfaces import Time

    class SimStamped(Node):
        def __init__(self, settings) -> None:
            super().__init__("sim_stamped", settings=settings)
            self.points = self.create_publisher(PointStamped, "/sim_stamped", 10)
            self.clock = self.create_publisher(Time, "/clock", 10)
            self.create_timer(0.02, self.tick)
            self.t = 100.0

        def tick(self) -> None:
            self.t += 0.02
            self.clock.publish(Time.from_sec(self.t))
            self.points.publish(PointStamped(header=Header(stamp=Time.from_sec(self.t - 0.5))))

    await start_node(SimStamped)
    status, out, _ = await skydeck(core.url, "topic", "delay", "/sim_stamped", "--use-sim-time", "-n", "2")
    delays = [float(line.split(":")[1]) for line in out.splitlines() if line.startswith("average delay:")]
    assert status == 0 and delays and 0.3 < delays[-1] < 0.7  # half a second of sim time, not 1.7e9 s


async def test_service_type_and_find(core, start_node) -> None:
    await start_node(Stamped)
    status, out, _ = await skydeck(core.url, "service", "type", "/stamped/enable")
    assert out == "std_srvs/srv/SetBool\n"
    status, out, _ = await skydeck(core.url, "service", "find", "std_srvs/srv/Trigger")
    assert status == 0 and out.splitlines() == ["/stamped/ping", "/stamped/stall"]
    status, _, err = await skydeck(core.url, "service", "find", "std_msgs/msg/String")
    assert status == 1 and "topic find" in err
    status, _, err = await skydeck(core.url, "service", "type", "/stamped/nope")
    assert status == 1 and "unknown service /stamped/nope" in err


async def test_node_ping(core, start_node) -> None:
    await start_node(Stamped)
    status, out, _ = await skydeck(core.url, "node", "ping", "stamped", "-c", "2", "--timeout", "2")
    assert status == 0 and out.count("reply from http://127.0.0.1:") == 2
    status, _, err = await skydeck(core.url, "node", "ping", "/nobody")
    assert status == 1 and "unknown node /nobody" in err


async def test_node_kill_stops_a_node_no_launch_manages(core) -> None:
    """A node started on its own (`skydeck run`) is stopped with SIGTERM, as rosnode kill would."""
    env_url = core.url
    node = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "run", "examples/send_message.py", "--core-url", env_url,
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )
    try:
        async with asyncio.timeout(20):
            while "/send_message_node" not in core.registry.nodes:
                await asyncio.sleep(0.05)
        status, out, err = await skydeck(core.url, "node", "kill", "/send_message_node")
        assert status == 0 and f"(pid {node.pid}) with SIGTERM" in out, err
        async with asyncio.timeout(10):
            assert await node.wait() == 0  # a clean stop: spin() handles SIGTERM
    finally:
        if node.returncode is None:
            node.kill()
            await node.wait()
    status, _, err = await skydeck(core.url, "node", "kill", "/skydeck_core")
    assert status == 1 and "part of Skydeck itself" in err


async def test_doctor_says_what_is_wrong_and_what_to_do(core) -> None:
    status, out, _ = await skydeck(core.url, "doctor")
    assert f"[ok] core at {core.url} answers" in out and "[ok] Python 3." in out
    assert ("[FAIL]" in out) == (status == 1), out
    assert "Chromium" in out and "ports" in out and "clock skew" in out
    # The ports the Skydeck it found holds are as they should be (issue 32): no warning for them.
    assert f"[ok] ports held by the Skydeck found at {core.url}: {core.port} (core)" in out, out
    assert status == 0 and out.rstrip().endswith(("Skydeck can run; all checks passed", "warning(s) above)")), out
    url = f"http://127.0.0.1:{free_port()}"
    status, out, _ = await skydeck(url, "doctor")
    assert status == 1 and f"[FAIL] core at {url} not reachable" in out and "-> start it with `skydeck core`" in out


def test_doctor_counts_what_only_the_tests_need_as_warnings(monkeypatch, tmp_path) -> None:
    """A machine that only runs Skydeck: no Chromium, Playwright, docker-compose or Node."""
    from services.cli import doctor

    monkeypatch.setattr(doctor, "_CHROMIUM", tmp_path / "no-chromium")
    monkeypatch.setattr(doctor.shutil, "which", lambda name, *args, **kwargs: None)
    monkeypatch.setattr(doctor.importlib.util, "find_spec", lambda name, *args: None)
    findings = doctor._browser() + doctor._test_tools()
    assert [finding.status for finding in findings] == ["warn"] * len(findings) and len(findings) == 4, findings
    assert {"Chromium", "Playwright", "docker-compose", "Node.js"} == {
        word for finding in findings for word in ("Chromium", "Playwright", "docker-compose", "Node.js") if word in finding.what
    }


def test_doctor_exits_0_when_nothing_runs_yet_and_the_ports_are_free(monkeypatch, capsys) -> None:
    """No SKYDECK_CORE_URL and no core: a warning, not a failure; the system can run."""
    from services.cli import doctor
    from services.cli.main import main

    monkeypatch.delenv("SKYDECK_CORE_URL", raising=False)
    monkeypatch.setattr(doctor, "_default_ports", lambda: {free_port(): "core"})
    monkeypatch.setattr(doctor, "core_url", lambda: f"http://127.0.0.1:{free_port()}")
    assert main(["doctor"]) == 0
    out = capsys.readouterr().out
    assert "[warn] no core running" in out and "[FAIL]" not in out and "Skydeck can run" in out, out


# -- shell completion -----------------------------------------------------------------------


def _bash_complete(core_url: str, line: str) -> list[str]:
    """Complete ``line`` (the last word partly typed) in a real bash with the script sourced."""
    script = (
        "source <(\"$SKYDECK\" completion bash)\n"
        'read -ra COMP_WORDS <<< "$LINE"\n'
        '[[ "$LINE" == *" " ]] && COMP_WORDS+=("")\n'
        "COMP_CWORD=$((${#COMP_WORDS[@]} - 1))\n"
        'COMP_WORDS[0]="$SKYDECK"\n'
        "_skydeck\n"
        'printf "%s\\n" "${COMPREPLY[@]}"\n'
    )
    skydeck_bin = shutil.which("skydeck", path=str(__import__("pathlib").Path(sys.executable).parent))
    result = subprocess.run(
        ["bash", "-c", script],
        env={"PATH": "/usr/bin:/bin", "LINE": line, "SKYDECK": skydeck_bin or "skydeck", "SKYDECK_CORE_URL": core_url},
        capture_output=True, text=True, timeout=30, cwd="tests/services/bag",
    )
    assert result.returncode == 0, result.stderr
    return [word for word in result.stdout.splitlines() if word]


LAUNCH_WITH_ARGUMENTS = "arguments:\n  rate: {default: '1'}\n  world: {}\nnodes: [{name: core, run: core, port_offset: 0}]\n"


async def test_bash_completes_verbs_flags_live_names_types_and_files(core, start_node, tmp_path) -> None:
    await start_node(Stamped)
    launch_file = tmp_path / "my_launch.yaml"
    launch_file.write_text(LAUNCH_WITH_ARGUMENTS)

    def complete(line: str) -> list[str]:
        return _bash_complete(core.url, line)

    assert await asyncio.to_thread(complete, "skydeck to") == ["topic"]
    assert "echo" in await asyncio.to_thread(complete, "skydeck topic ")
    assert await asyncio.to_thread(complete, "skydeck topic echo --f") == ["--field"]
    assert await asyncio.to_thread(complete, "skydeck topic echo /st") == ["/stamped"]
    assert await asyncio.to_thread(complete, "skydeck service call /stamped/p") == ["/stamped/ping"]
    assert await asyncio.to_thread(complete, "skydeck node info /sta") == ["/stamped"]
    assert await asyncio.to_thread(complete, "skydeck interface show sensor_msgs/msg/LaserS") == ["sensor_msgs/msg/LaserScan"]
    assert "std_srvs/srv/Trigger" in await asyncio.to_thread(complete, "skydeck service find std_srvs/")
    assert await asyncio.to_thread(complete, "skydeck bag info test_f") == ["test_files.py"]  # a path
    assert await asyncio.to_thread(complete, "skydeck bag record -o test_r") == ["test_record_play.py"]
    assert await asyncio.to_thread(complete, "skydeck run con") == ["control"]
    assert await asyncio.to_thread(complete, f"skydeck launch {launch_file} ") == ["rate:=", "world:="]
    assert await asyncio.to_thread(complete, f"skydeck launch {launch_file} --speed 2 rate:=3 w") == ["world:="]


class FibonacciServer(Node):
    """Serves the action /fibonacci (goals are accepted and left waiting)."""

    def __init__(self, settings) -> None:
        from services.runtime.actions import ActionServer
        from shared_models import get_interface

        super().__init__("fibonacci_server", settings=settings)

        async def accept(goal) -> bool:
            return True

        ActionServer(self, get_interface("example_interfaces/action/Fibonacci"), "fibonacci",
                     on_goal=accept, on_cancel=accept, on_accepted=lambda goal: None)  # fmt: skip


async def test_bash_completes_action_names_and_types(core, start_node) -> None:
    await start_node(FibonacciServer)

    def complete(line: str) -> list[str]:
        return _bash_complete(core.url, line)

    assert await asyncio.to_thread(complete, "skydeck act") == ["action"]
    assert await asyncio.to_thread(complete, "skydeck action info /fi") == ["/fibonacci"]
    assert await asyncio.to_thread(complete, "skydeck action send_goal /fibonacci example_interfaces/action/F") == [
        "example_interfaces/action/Fibonacci"]  # fmt: skip


def _zsh_complete(core_url: str, lines: list[str], cwd: Path) -> list[tuple[list[str], str]]:
    """Complete each of ``lines`` in a real interactive zsh (compinit, the script sourced, Tab
    pressed in a pseudo-terminal: zsh_complete.zsh); for each, what was offered and the line after."""
    assert shutil.which("zsh"), "zsh is a test dependency: run `make test-deps`"
    result = subprocess.run(
        ["zsh", "-f", str(Path(__file__).with_name("zsh_complete.zsh")), *lines],
        env={"PATH": f"{Path(sys.executable).parent}:/usr/bin:/bin", "HOME": str(cwd), "SKYDECK_CORE_URL": core_url},
        capture_output=True, text=True, timeout=90, cwd=cwd,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    answers = [line.split("\t") for line in result.stdout.splitlines()]
    assert len(answers) == len(lines), result.stdout
    return [(offered.split("|") if offered else [], buffer) for offered, buffer in answers]


@pytest.mark.timeout(120)
async def test_zsh_completes_verbs_flags_live_names_and_files(core, start_node, tmp_path) -> None:
    await start_node(Stamped)
    (tmp_path / "my_launch.yaml").write_text(LAUNCH_WITH_ARGUMENTS)
    lines = {
        "skydeck to": (["topic"], "skydeck topic "),
        "skydeck topic echo --f": (["--field"], "skydeck topic echo --field "),
        "skydeck topic echo /st": (["/stamped"], "skydeck topic echo /stamped "),
        "skydeck service call /stamped/p": (["/stamped/ping"], "skydeck service call /stamped/ping "),
        "skydeck node info /sta": (["/stamped"], "skydeck node info /stamped "),
        "skydeck launch my_l": (["my_launch.yaml"], "skydeck launch my_launch.yaml "),  # a path, from _files
        "skydeck launch my_launch.yaml rate:=2 ": (["world:="], "skydeck launch my_launch.yaml rate:=2 world:="),  # no space
    }
    answers = await asyncio.to_thread(_zsh_complete, core.url, [*lines, "skydeck topic "], tmp_path)
    assert dict(zip(lines, answers[:-1], strict=True)) == lines
    offered, buffer = answers[-1]
    assert {"echo", "hz", "pub", "type"} <= set(offered) and buffer == "skydeck topic "  # several: listed


async def test_topic_list_verbose_counts_publishers_and_subscribers(core, start_node) -> None:
    await start_node(Stamped)
    status, out, _ = await skydeck(core.url, "topic", "list", "--verbose")
    assert status == 0 and "/stamped 1 publisher(s), 0 subscriber(s)" in out.splitlines()


async def test_server_flags_of_core_and_run(tmp_path) -> None:
    """--host, --port, --advertise-url and --log-level reach the core and a node."""
    from services.launch.background import BackgroundProcess
    from tests.conftest import free_port_block

    base = free_port_block(2)
    core_url, node_url = f"http://127.0.0.1:{base}", f"http://localhost:{base + 1}"
    env = {**__import__("os").environ, "SKYDECK_CORE_URL": core_url, "PYTHONUNBUFFERED": "1"}
    core = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "core", "--host", "127.0.0.1", "--port", str(base),
         "--advertise-url", core_url, "--log-level", "warning"], name="core", env=env,
    )  # fmt: skip
    node = None
    try:
        await asyncio.to_thread(core.wait_healthy, core_url + "/health", 30)
        node = BackgroundProcess(
            [sys.executable, "-m", "services.cli", "run", "perception", "--host", "127.0.0.1", "--port", str(base + 1),
             "--advertise-url", node_url, "--log-level", "debug"], name="perception", env=env,
        )  # fmt: skip
        await node.await_line("registered with core", 30)  # an INFO line: shown at --log-level debug
        status, out, _ = await skydeck(core_url, "node", "info", "/perception")
        assert status == 0 and f"URI: {node_url}" in out  # the advertised URL, not the bound one
    finally:
        if node is not None:
            node.stop()
        core.stop()
