"""One graded run: a private core and simulator on free loopback ports, the recorder, the support
nodes and the student's nodes, stepped in lockstep for the run's length, then torn down. The
core and the recorder are hosted in this process (:mod:`.hosted`); the rest are processes.

    result = await run_world(RunPlan(world="robot", seed=1, options={"obstacles": 0},
                                     duration_s=20.0, nodes=[NodeCommand("wall_follower")],
                                     out_dir=Path("out/seed-1")))
    result.bag            # the recording (MCAP)

Every other process is a ``skydeck`` command, started as a user would (``skydeck run FILE``), with
``SKYDECK_LOCKSTEP_URL`` pointing at this run's coordinator (:mod:`.coordinator`) and, for the
nodes, ``--use-sim-time``. Before the first step the run waits until every process has joined,
every node is linked to every publisher of what it reads, and the recorder records every topic:
the first step then finds every run in the same state.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import re
import sys
import time
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

from services.grading.coordinator import Coordinator, LockstepError
from services.grading.hosted import NOT_RECORDED, HostedCore, HostedRecorder
from services.launch.background import BackgroundProcess, ProcessFailed
from services.runtime.lockstep.frames import ReportFrame
from shared_models.errors import SkydeckError

__all__ = ["NodeCommand", "NodeOutcome", "RunFailed", "RunPlan", "RunResult", "run_world"]

_START_TIMEOUT_S = 60.0  # processes importing PyBullet and the SDK on a loaded 2-core machine
_READY_TIMEOUT_S = 30.0
_POLL_S = 0.05


class RunFailed(SkydeckError):
    """The run's own parts (core, simulator, recorder) did not start or keep running."""


@dataclass(frozen=True)
class NodeCommand:
    """One process to run: a built-in node's name or a ``.py`` file, with ROS parameters."""

    target: str
    parameters: dict[str, object] = field(default_factory=dict)
    student: bool = True
    """False for the assignment's support nodes (the drone's control and perception)."""

    @property
    def label(self) -> str:
        return Path(self.target).name


@dataclass(frozen=True)
class RunPlan:
    world: str
    seed: int
    options: dict[str, object]
    """The world's own options (``obstacles``, ``boxes``...)."""
    duration_s: float
    nodes: list[NodeCommand]
    out_dir: Path


@dataclass
class NodeOutcome:
    label: str
    student: bool
    exit_code: int | None
    """None: it ran until the run ended."""
    log: Path
    hung: bool = False
    """It stayed busy (or stopped answering) for a whole settle: the run stopped it and went on."""


@dataclass
class RunResult:
    bag: Path
    sim_time_s: float
    wall_time_s: float
    steps: int
    lockstep_lost: int
    lockstep_reason: str
    nodes: list[NodeOutcome]
    stepping_wall_s: float = 0.0
    """Wall time of the steps alone (the rest is starting and stopping processes)."""
    stepping_cpu_s: dict[str, float] = field(default_factory=dict)
    """CPU time each process spent during the steps (this process as ``grader``)."""


def _argv(*args: object) -> list[str]:
    return [sys.executable, "-m", "services.cli", *(str(a) for a in args)]


def _ros_parameters(parameters: dict[str, object]) -> list[str]:
    if not parameters:
        return []
    args = ["--ros-args"]
    for name, value in parameters.items():
        text = json.dumps(value) if isinstance(value, bool | int | float | list) else str(value)
        args += ["-p", f"{name}:={text}"]
    return args


class _Run:
    """The processes of one run and their teardown."""

    def __init__(self, plan: RunPlan) -> None:
        self.plan = plan
        plan.out_dir.mkdir(parents=True, exist_ok=True)
        self.core = HostedCore()
        self.coordinator = Coordinator()
        self.recorder: HostedRecorder | None = None
        self.processes: dict[str, BackgroundProcess] = {}
        self.node_processes: list[tuple[NodeCommand, BackgroundProcess]] = []
        self.hung: set[int] = set()  # the pids of the student's nodes stopped for never settling
        self.bag = plan.out_dir / "run.mcap"
        self.bag.unlink(missing_ok=True)  # a run graded again replaces its recording

    def _env(self, lockstep_url: str) -> dict[str, str]:
        env = {key: value for key, value in os.environ.items() if not key.startswith(("SKYDECK_", "ROS_"))}
        env.update({
            "SKYDECK_CORE_URL": self.core.url,
            "SKYDECK_LOCKSTEP_URL": lockstep_url,
            "SKYDECK_STATE_DIR": str(self.plan.out_dir / "state"),
            "PYTHONUNBUFFERED": "1",
        })  # fmt: skip
        return env

    def _start(self, name: str, argv: list[str], env: dict[str, str], cwd: Path | None = None) -> BackgroundProcess:
        log = self.plan.out_dir / f"{name}.log"
        process = BackgroundProcess(argv, name=name, env=env, cwd=cwd, log_path=log)
        self.processes[name] = process
        return process

    async def start(self) -> None:
        """The core and the coordinator here, then the simulator and the nodes, then the recorder."""
        await self.core.start()
        lockstep_url = await self.coordinator.start()
        env = self._env(lockstep_url)
        plan = self.plan
        options: list[object] = []
        for name, value in plan.options.items():
            options += [f"--{name.replace('_', '-')}", value]
        self._start("sim", _argv("run", "sim", "--world", plan.world, "--seed", plan.seed, "--speed", "max",
                                 "--port", 0, *options), env)  # fmt: skip
        used: dict[str, int] = {}
        for command in plan.nodes:
            label = command.label.removesuffix(".py")
            used[label] = used.get(label, 0) + 1
            name = label if used[label] == 1 else f"{label}_{used[label]}"
            target = command.target
            cwd = None
            if target.endswith(".py"):
                path = Path(target).resolve()
                target, cwd = str(path), path.parent
            argv = _argv("run", target, "--use-sim-time", "--port", 0, *_ros_parameters(command.parameters))
            self.node_processes.append((command, self._start(f"node-{name}", argv, env, cwd)))
        self.recorder = HostedRecorder(
            self.bag, self.core.url, lockstep_url, seed=plan.seed,
            command_line=f"skydeck grade ({plan.world} world, seed {plan.seed})",
        )  # fmt: skip
        await self.recorder.start()

    async def wait_ready(self) -> None:
        """Until every process joined, links are made and the recorder reads every topic."""
        deadline = time.monotonic() + _START_TIMEOUT_S
        while True:
            self._check_own_processes()
            started = [p for _, p in self.node_processes if p.returncode is None]
            expected = 2 + len(started)  # this process (the recorder), the simulator, the nodes
            if len(self.coordinator.processes) >= expected:
                break
            if time.monotonic() > deadline:
                raise RunFailed(f"the run's processes did not all join within {_START_TIMEOUT_S:g} s")
            await self.coordinator.wait_for_processes(expected, _POLL_S)
        deadline = time.monotonic() + _READY_TIMEOUT_S
        while True:
            self._check_own_processes()
            reports = await self.coordinator.reports()
            missing = _missing_links(reports, await asyncio.to_thread(self._graph))
            if missing is None and await self.coordinator.settle():
                return
            if time.monotonic() > deadline:
                raise RunFailed(f"the run was not ready within {_READY_TIMEOUT_S:g} s: {missing or 'not settled'}")
            await asyncio.sleep(_POLL_S)

    def cpu_seconds(self) -> dict[str, float]:
        """CPU time so far of each process still running, and of this one (``grader``: the
        coordinator, the core and the recorder)."""
        seconds = {"grader": time.process_time()}
        for name, process in self.processes.items():
            if process.returncode is None:
                with contextlib.suppress(OSError, ValueError):
                    seconds[name] = process.cpu_seconds()
        return seconds

    def _graph(self) -> dict[str, object]:
        with urllib.request.urlopen(f"{self.core.url}/api/graph", timeout=5.0) as reply:
            graph: dict[str, object] = json.loads(reply.read())
        return graph

    def stop_stuck_nodes(self, pids: list[int]) -> None:
        """Stop the student's node processes among ``pids`` (busy for a whole settle: a loop that
        never ends, a blocked event loop): the run goes on without them, as after a crash."""
        for command, process in self.node_processes:
            if command.student and process.returncode is None and _leads(process.pid, pids):
                process.stop(timeout_s=2.0)
                self.hung.add(process.pid)

    def _check_own_processes(self) -> None:
        process = self.processes.get("sim")
        if process is not None and process.returncode is not None:
            raise RunFailed(f"the run's simulator exited ({process.returncode}):\n{process.tail(15)}")

    async def stop(self) -> None:
        """The recorder first (the run has settled: it holds every message) and its file
        finished, then every process at once, then the core."""
        if self.recorder is not None:
            await self.recorder.stop()
        await asyncio.gather(*(asyncio.to_thread(p.stop) for p in self.processes.values()))
        await self.coordinator.stop()
        await self.core.stop()


def _leads(leader: int, pids: list[int]) -> bool:
    """Whether ``leader``'s process group (a started process leads its own) holds one of ``pids``."""
    for pid in pids:
        with contextlib.suppress(OSError):
            if pid == leader or os.getpgid(pid) == leader:
                return True
    return False


def _missing_links(reports: list[ReportFrame], graph: dict[str, object]) -> str | None:
    """What is not yet linked in the run: a node of the run that reads a topic a node of the run
    publishes without a link to it, or a topic the recorder does not read yet; None when all is."""
    received = {(node.name, topic, peer) for report in reports for node in report.nodes for topic, peer, _ in node.received}
    names = {node.name for report in reports for node in report.nodes}
    recorders = [name for name in names if name.startswith("/bag_record_")]
    topics = graph.get("topics")
    for topic in topics if isinstance(topics, list) else []:
        publishers = [p for p in topic.get("publishers", []) if p in names]
        if not publishers or re.search(NOT_RECORDED, topic["name"]):
            continue
        subscribers = set(topic.get("subscribers", []))
        for recorder in recorders:
            if recorder not in subscribers:
                return f"the recorder does not read {topic['name']} yet"
        for reader in subscribers & names:
            for publisher in publishers:
                if publisher != reader and (reader, topic["name"], publisher) not in received:
                    return f"{reader} is not linked to {publisher} for {topic['name']} yet"
    return None


async def run_world(plan: RunPlan) -> RunResult:
    """Run ``plan`` to its length in lockstep and return what it recorded (see the module docstring).

    Raises RunFailed when the core, the simulator or the recorder fails; a student's node that
    fails is reported in ``nodes`` (its log beside the recording) and the run goes on without it.
    """
    run = _Run(plan)
    started = time.monotonic()
    steps = 0
    sim_time_s = 0.0
    try:
        await run.start()
        await run.wait_ready()
        coordinator = run.coordinator
        stepping_from, cpu_from = time.monotonic(), run.cpu_seconds()
        stepped = await coordinator.step("start")
        if not await coordinator.settle(after=stepped):
            await asyncio.to_thread(run.stop_stuck_nodes, coordinator.settling.stuck)
        sim_time_s = stepped.time_s
        while sim_time_s < plan.duration_s - 1e-9:
            stepped = await coordinator.step("advance")
            if not await coordinator.settle(after=stepped):
                await asyncio.to_thread(run.stop_stuck_nodes, coordinator.settling.stuck)
            sim_time_s = stepped.time_s
            steps += 1
            if steps % 30 == 0:
                run._check_own_processes()
        stepping_wall_s = time.monotonic() - stepping_from
        cpu_to = run.cpu_seconds()
        stepping_cpu_s = {name: cpu_to[name] - cpu_from[name] for name in cpu_to if name in cpu_from}
        exit_codes = [process.returncode for _, process in run.node_processes]  # before they are stopped
    except (LockstepError, ProcessFailed) as error:
        raise RunFailed(str(error)) from None
    finally:
        await run.stop()
    outcomes = [
        NodeOutcome(
            label=command.label,
            student=command.student,
            exit_code=code,
            log=process.log_path or plan.out_dir,
            hung=process.pid in run.hung,
        )
        for (command, process), code in zip(run.node_processes, exit_codes, strict=True)
    ]
    return RunResult(
        bag=run.bag,
        sim_time_s=sim_time_s,
        wall_time_s=time.monotonic() - started,
        steps=steps,
        lockstep_lost=run.coordinator.settling.lost,
        lockstep_reason=run.coordinator.settling.last_reason,
        nodes=outcomes,
        stepping_wall_s=stepping_wall_s,
        stepping_cpu_s=stepping_cpu_s,
    )
