"""The supervisor with real processes: small programs that serve /health stand in for nodes."""

from __future__ import annotations

import asyncio
import io
import os
import re
import signal
import socket
import subprocess
import sys
import textwrap
from collections.abc import Sequence
from pathlib import Path

import httpx
import pytest

from services.launch import (
    CommandFor,
    LaunchError,
    LaunchFileError,
    LaunchOptions,
    LaunchSpec,
    NodePlan,
    NodeSpec,
    NodeState,
    Supervisor,
    run_launch,
)
from tests.conftest import free_port_block

pytestmark = pytest.mark.timeout(30)

REPO = Path(__file__).resolve().parents[3]

# A stand-in node. It prints a line on stdout with what it was given, then serves GET /health on
# --port; flags make it exit at once, spawn a grandchild, never serve, serve only once a file
# exists, create a file, or ignore SIGTERM.
NODE_PROGRAM = textwrap.dedent(
    """\
    import argparse, http.server, os, signal, subprocess, sys, time

    parser = argparse.ArgumentParser()
    parser.add_argument("--port", type=int, required=True)
    parser.add_argument("--exit", type=int)
    parser.add_argument("--grandchild")
    parser.add_argument("--no-health", action="store_true")
    parser.add_argument("--ignore-term", action="store_true")
    parser.add_argument("--health-after")
    parser.add_argument("--touch")
    args, _ = parser.parse_known_args()  # a core's endpoint ports too (--rosbridge-port ...)
    print(f"hello on {args.port} core={os.environ.get('SKYDECK_CORE_URL')} "
          f"extra={os.environ.get('EXTRA', '')} grace={os.environ.get('SKYDECK_CORE_START_GRACE_S', '')}")
    if args.exit is not None:
        print("boom: cannot go on", file=sys.stderr)
        sys.exit(args.exit)
    if args.ignore_term:
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
    if args.grandchild:
        child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
        with open(args.grandchild + ".tmp", "w") as file:
            file.write(str(child.pid))
        os.replace(args.grandchild + ".tmp", args.grandchild)
    if args.no_health:
        time.sleep(60)
    if args.touch:
        open(args.touch, "w").close()
    while args.health_after and not os.path.exists(args.health_after):
        time.sleep(0.01)

    class Health(http.server.BaseHTTPRequestHandler):
        def do_GET(self):
            self.send_response(200 if self.path == "/health" else 404)
            self.send_header("Content-Length", "2")
            self.end_headers()
            self.wfile.write(b"ok")

        def log_message(self, *args):
            pass

    http.server.HTTPServer(("127.0.0.1", args.port), Health).serve_forever()
    """
)


# --- helpers --------------------------------------------------------------------------------


def alive(pid: int) -> bool:
    """True while ``pid`` is a live process (a zombie waiting for its reaper counts as gone)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except (FileNotFoundError, ProcessLookupError):
        return False
    return stat.rsplit(")", 1)[1].split()[0] not in ("Z", "X")


async def wait_gone(pids: Sequence[int], timeout_s: float = 5.0) -> None:
    """Wait for processes reparented to init to be reaped (nothing to await but their absence)."""
    async with asyncio.timeout(timeout_s):
        while any(alive(pid) for pid in pids):
            await asyncio.sleep(0.02)


@pytest.fixture
def program(tmp_path: Path) -> Path:
    path = tmp_path / "node_program.py"
    path.write_text(NODE_PROGRAM)
    return path


def command_for(program: Path):  # type: ignore[no-untyped-def]
    """Every node, the core included, is the stand-in program."""

    def command(plan: NodePlan) -> list[str]:
        return [sys.executable, str(program), "--port", str(plan.port), *plan.args]

    return command


def node(name: str, offset: int, *args: str, **fields: object) -> NodeSpec:
    return NodeSpec(name=name, run=f"{name}.py", port_offset=offset, args=args, **fields)  # type: ignore[arg-type]


def ready_names(out: io.StringIO) -> list[str]:
    return re.findall(r"^\[launch\] (\S+) ready at ", out.getvalue(), flags=re.M)


class Launch:
    """A supervisor on free ports with captured output; always stopped at the end of the test."""

    def __init__(self, program: Path) -> None:
        self.program = program
        self.out = io.StringIO()
        self.supervisors: list[Supervisor] = []

    def __call__(
        self,
        *nodes: NodeSpec,
        stop_timeout_s: float = 5.0,
        command: CommandFor | None = None,
        **options: object,
    ) -> Supervisor:
        base = free_port_block(max(n.port_offset for n in nodes) + 1)
        supervisor = Supervisor(
            LaunchSpec(nodes=nodes),
            LaunchOptions(base_port=base, **options),  # type: ignore[arg-type]
            command_for=command or command_for(self.program),
            out=self.out,
            stop_timeout_s=stop_timeout_s,
        )
        self.supervisors.append(supervisor)
        return supervisor


@pytest.fixture
async def launch(program: Path):  # type: ignore[no-untyped-def]
    launcher = Launch(program)
    yield launcher
    for supervisor in launcher.supervisors:
        await supervisor.stop()


# --- starting -------------------------------------------------------------------------------


async def test_all_nodes_come_up_in_order(launch: Launch) -> None:
    supervisor = launch(node("a", 0), node("b", 1), node("c", 2))
    await supervisor.start()
    assert ready_names(launch.out) == ["a", "b", "c"]
    async with httpx.AsyncClient() as client:
        for name in ("a", "b", "c"):
            status = supervisor.status(name)
            assert status.state is NodeState.READY
            assert status.ready_count == 1 and status.restarts == 0
            assert status.pid is not None and alive(status.pid)
            assert (await client.get(f"{status.url}/health")).status_code == 200
    text = launch.out.getvalue()
    base = supervisor.options.base_port
    assert re.search(
        rf"^\[launch\] a ready at http://127\.0\.0\.1:{base} \(pid \d+, \d+\.\d s\)$", text, re.M
    )
    assert re.search(rf"^\[b\] hello on {base + 1} ", text, re.M)
    assert "[launch] all 3 nodes up; Ctrl-C stops them" in text


async def test_the_nodes_start_together_with_the_core(launch: Launch, tmp_path: Path) -> None:
    # a answers only once c has started: one after the other, c would never start
    flag = str(tmp_path / "c-started")
    hub = NodeSpec(name="hub", run="core", port_offset=0, args=("--health-after", flag))
    supervisor = launch(hub, node("a", 1, "--health-after", flag), node("b", 2), node("c", 3, "--touch", flag))
    await supervisor.start()
    assert ready_names(launch.out) == ["hub", "a", "b", "c"]  # said in launch order all the same
    # the nodes beside the core are told to wait for it quietly while it starts, the core is not
    text = launch.out.getvalue()
    assert re.search(r"^\[a\] hello .* grace=20$", text, re.M) and re.search(r"^\[hub\] hello .* grace=$", text, re.M)


async def test_the_core_starts_first_and_every_node_is_told_where_it_is(launch: Launch) -> None:
    supervisor = launch(node("a", 1), NodeSpec(name="hub", run="core", port_offset=3), node("b", 2))
    await supervisor.start()
    assert ready_names(launch.out) == ["hub", "a", "b"]
    core = f"http://127.0.0.1:{supervisor.options.base_port + 3}"
    assert supervisor.core_url == core
    assert launch.out.getvalue().count(f" core={core} ") == 3


async def test_placeholders_and_env_reach_the_node(launch: Launch) -> None:
    supervisor = launch(
        node("a", 0, env={"EXTRA": "{base_port}/{seed}/{boxes}/{speed}"}),
        seed=7,
        world_options={"boxes": 3},
        speed="max",
    )
    await supervisor.start()
    assert f"extra={supervisor.options.base_port}/7/3/max" in launch.out.getvalue()


async def test_a_drawn_seed_is_announced(launch: Launch) -> None:
    supervisor = launch(node("a", 0, env={"EXTRA": "{seed}"}))
    await supervisor.start()
    seed = supervisor.options.seed
    assert (
        f"[launch] world seed {seed} (--seed {seed} gives the same world again)"
        in launch.out.getvalue()
    )
    assert f"extra={seed}" in launch.out.getvalue()


async def test_exclude_leaves_nodes_out(launch: Launch) -> None:
    supervisor = launch(node("a", 0), node("b", 1), node("c", 2), exclude=("b",))
    await supervisor.start()
    assert ready_names(launch.out) == ["a", "c"]
    with pytest.raises(LaunchError, match="no node 'b' in this launch; its nodes are: a, c"):
        supervisor.status("b")


def test_exclude_of_an_unknown_node(program: Path) -> None:
    spec = LaunchSpec(nodes=(node("a", 0),))
    with pytest.raises(LaunchError, match="--exclude names 'zz'"):
        Supervisor(spec, LaunchOptions(exclude=("zz",)), command_for=command_for(program))


# --- a node that cannot start -----------------------------------------------------------------


async def test_a_node_that_exits_at_once_is_a_launch_error(launch: Launch, tmp_path: Path) -> None:
    grandchild = tmp_path / "a.pid"
    supervisor = launch(
        node("a", 0, "--grandchild", str(grandchild)), node("b", 1, "--exit", "3"), node("c", 2)
    )
    with pytest.raises(LaunchError) as caught:
        await supervisor.start()
    assert str(caught.value) == "b exited with exit code 3 before it was ready: boom: cannot go on"
    assert (caught.value.node, caught.value.exit_code) == ("b", 3)
    assert caught.value.stderr_tail == ("boom: cannot go on",)
    # The nodes start together (none is the core here): each is stopped again, grandchild
    # included; the ready lines come in launch order, up to the one that failed.
    assert ready_names(launch.out) == ["a"]
    assert supervisor.status("a").state is NodeState.STOPPED
    assert supervisor.status("c").state is NodeState.STOPPED and supervisor.status("c").restarts == 0
    await wait_gone([int(grandchild.read_text())])
    assert "[b] boom: cannot go on" in launch.out.getvalue()


async def test_a_node_that_never_answers_times_out(launch: Launch) -> None:
    supervisor = launch(node("a", 0, "--no-health", ready_timeout_s=0.5))
    with pytest.raises(
        LaunchError,
        match=r"^a \(pid \d+\) did not answer http://127\.0\.0\.1:\d+/health within 0\.5 s; is it serving on port \d+\?$",
    ):
        await supervisor.start()
    assert supervisor.status("a").state is NodeState.STOPPED
    assert supervisor.status("a").pid is None


async def test_a_command_that_cannot_run(launch: Launch) -> None:
    supervisor = launch(node("a", 0), command=lambda plan: ["/nonexistent/skydeck-node"])
    with pytest.raises(
        LaunchError, match=r"^cannot start a \(/nonexistent/skydeck-node\): \[Errno 2\]"
    ):
        await supervisor.start()


async def test_a_port_in_use_is_refused_before_anything_starts(launch: Launch) -> None:
    supervisor = launch(node("a", 0), node("b", 1))
    with socket.socket() as squatter:
        squatter.bind(("127.0.0.1", supervisor.options.base_port + 1))
        squatter.listen()
        with pytest.raises(LaunchError, match=r"port \d+ for b is already in use"):
            await supervisor.start()
    assert ready_names(launch.out) == []
    assert supervisor.status("a").state is NodeState.WAITING


# --- respawning -----------------------------------------------------------------------------


async def test_a_killed_node_is_respawned(launch: Launch, tmp_path: Path) -> None:
    grandchild = tmp_path / "b.pid"
    supervisor = launch(node("a", 0), node("b", 1, "--grandchild", str(grandchild)))
    await supervisor.start()
    first = supervisor.status("b")
    first_grandchild = int(grandchild.read_text())
    assert first.pid is not None
    os.kill(first.pid, signal.SIGKILL)
    async with asyncio.timeout(10):
        again = await supervisor.wait_ready("b", count=2)
    assert again.pid is not None and again.pid != first.pid
    assert (again.state, again.ready_count, again.restarts) == (NodeState.READY, 2, 1)
    assert again.exit_code == -signal.SIGKILL
    text = launch.out.getvalue()
    assert re.search(
        r"^\[launch\] b exited with signal SIGKILL after \d+\.\d s; respawning in 0\.5 s$",
        text,
        re.M,
    )
    assert re.search(
        rf"^\[launch\] b ready at .* \(pid {again.pid}, \d+\.\d s, restart 1\)$", text, re.M
    )
    # The dead node's grandchild was cleaned up; the new one has its own.
    await wait_gone([first_grandchild])
    assert supervisor.status("a").ready_count == 1


async def test_respawn_backs_off_while_a_node_keeps_dying(launch: Launch) -> None:
    supervisor = launch(node("a", 0))
    await supervisor.start()
    for count in (2, 3):
        pid = supervisor.status("a").pid
        assert pid is not None
        os.kill(pid, signal.SIGKILL)
        async with asyncio.timeout(10):
            await supervisor.wait_ready("a", count=count)
    text = launch.out.getvalue()
    assert "respawning in 0.5 s" in text and "respawning in 1 s" in text


async def test_a_node_without_respawn_stays_down(launch: Launch) -> None:
    supervisor = launch(node("a", 0), node("b", 1, respawn=False))
    await supervisor.start()
    pid = supervisor.status("b").pid
    assert pid is not None
    os.kill(pid, signal.SIGTERM)
    with pytest.raises(LaunchError, match=r"b exited \(code -15\) and is not respawned"):
        async with asyncio.timeout(10):
            await supervisor.wait_ready("b", count=2)
    assert (
        "[launch] b exited with signal SIGTERM; not respawned (respawn: false)"
        in launch.out.getvalue()
    )
    assert supervisor.status("a").state is NodeState.READY


# --- stopping -------------------------------------------------------------------------------


async def test_stop_leaves_no_process_behind(launch: Launch, tmp_path: Path) -> None:
    supervisor = launch(
        *(
            node(name, i, "--grandchild", str(tmp_path / f"{name}.pid"))
            for i, name in enumerate("abc")
        )
    )
    await supervisor.start()
    pids = [supervisor.status(name).pid for name in "abc"]
    grandchildren = [int((tmp_path / f"{name}.pid").read_text()) for name in "abc"]
    assert all(pid is not None and alive(pid) for pid in pids)
    assert all(alive(pid) for pid in grandchildren)
    await supervisor.stop()
    assert not any(alive(pid) for pid in pids if pid is not None)
    await wait_gone(grandchildren)
    stopped = re.findall(r"^\[launch\] (\S+) stopped \(", launch.out.getvalue(), flags=re.M)
    assert stopped == ["c", "b", "a"]  # reverse order
    assert all(supervisor.status(name).state is NodeState.STOPPED for name in "abc")
    await supervisor.stop()  # twice is fine
    with pytest.raises(LaunchError, match="is stopping"):
        await supervisor.wait_ready("a", count=2)


async def test_a_node_that_ignores_sigterm_is_killed(launch: Launch) -> None:
    supervisor = launch(node("a", 0, "--ignore-term"), stop_timeout_s=0.3)
    await supervisor.start()
    pid = supervisor.status("a").pid
    assert pid is not None
    await supervisor.stop()
    assert not alive(pid)
    assert "[launch] a did not stop within 0.3 s; killing it" in launch.out.getvalue()


async def test_stop_during_start_stops_what_started(launch: Launch) -> None:
    supervisor = launch(node("a", 0), node("b", 1, "--no-health"), node("c", 2))
    starting = asyncio.create_task(supervisor.start())
    async with asyncio.timeout(10):
        await supervisor.wait_ready("a")
        while supervisor.status("b").state is not NodeState.STARTING:
            await asyncio.sleep(0.01)  # no event marks "b's process exists"; it is one spawn away
    await supervisor.stop()
    await starting  # returns quietly: a stop was asked for
    assert ready_names(launch.out) == ["a"]  # c's line, if it came up, waits for b's: never said
    # a, b and c started together (none is the core here): all are stopped
    assert [supervisor.status(name).state for name in "abc"] == [NodeState.STOPPED] * 3


async def test_start_twice_is_an_error(launch: Launch) -> None:
    supervisor = launch(node("a", 0))
    await supervisor.start()
    with pytest.raises(LaunchError, match="already started"):
        await supervisor.start()


# --- the whole thing as a process, stopped by a signal ------------------------------------------

RUNNER = textwrap.dedent(
    """\
    import asyncio, sys
    from services.launch import LaunchOptions, LaunchSpec, NodeSpec, Supervisor

    program, base, pid_dir = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    spec = LaunchSpec(nodes=[
        NodeSpec(name=name, run=name + ".py", port_offset=i,
                 args=["--grandchild", f"{pid_dir}/{name}.pid"])
        for i, name in enumerate(["a", "b"])
    ])
    command = lambda plan: [sys.executable, program, "--port", str(plan.port), *plan.args]
    sys.exit(asyncio.run(Supervisor(spec, LaunchOptions(base_port=base), command_for=command).run()))
    """
)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_stops_everything_and_exits_0(
    program: Path, tmp_path: Path, sig: signal.Signals
) -> None:
    runner = tmp_path / "runner.py"
    runner.write_text(RUNNER)
    env = {**os.environ, "PYTHONPATH": str(REPO), "PYTHONUNBUFFERED": "1"}
    process = subprocess.Popen(
        [sys.executable, str(runner), str(program), str(free_port_block(2)), str(tmp_path)],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env,
    )
    try:
        lines = []
        assert process.stdout is not None
        for line in process.stdout:
            lines.append(line)
            if "all 2 nodes up" in line:
                break
        else:
            pytest.fail("the launch never came up:\n" + "".join(lines))
        pids = [int(pid) for pid in re.findall(r"ready at \S+ \(pid (\d+),", "".join(lines))]
        pids += [int((tmp_path / f"{name}.pid").read_text()) for name in "ab"]
        assert len(pids) == 4 and all(alive(pid) for pid in pids)
        process.send_signal(sig)
        rest, _ = process.communicate(timeout=15)
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == 0, "".join(lines) + rest
    assert f"[launch] {sig.name}: stopping" in rest
    assert "[launch] all nodes stopped" in rest
    asyncio.run(wait_gone(pids))


def test_run_launch_reports_a_bad_launch_file(tmp_path: Path) -> None:
    with pytest.raises(LaunchFileError, match=r"x\.yaml: no such launch file$"):
        run_launch(tmp_path / "x.yaml")
